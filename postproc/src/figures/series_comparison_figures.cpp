// The figures, the table of compared fits and the Markdown report of two series side by side.
#include "figures/series_comparison_figures.h"

#include <cmath>
#include <filesystem>
#include <functional>

#include "figures/series_figures.h"
#include "output/gnuplot.h"
#include "output/report.h"
#include "source/source_comparison.h"

namespace cdpost {

namespace {

const double kEveryFriction = NAN;  // the friction of a curve drawn for every friction

// How both series are drawn on one panel: a colour per friction (the same in both series), a
// point type and a line dash per series, each title in the key led by its series' label.
struct Styles {
  std::vector<double> frictions;  // of both series, ascending: line types 1, 2, ...
  std::array<std::string, 2> labels;

  explicit Styles(const SeriesComparison& comparison) : labels(comparison.labels)
  {
    for (const auto& series : comparison.series)
      for (const auto& run : series.runs) frictions.push_back(run.entry.mu);
    std::sort(frictions.begin(), frictions.end());
    frictions.erase(std::unique(frictions.begin(), frictions.end()), frictions.end());
  }
  // A curve of every friction (a law fitted over all of them, mu kEveryFriction) takes the next one.
  int line_type(double mu) const
  {
    if (std::isnan(mu)) return 1 + static_cast<int>(frictions.size());
    return 1 + static_cast<int>(std::find(frictions.begin(), frictions.end(), mu) - frictions.begin());
  }

  void add(Panel& panel, size_t series, std::vector<FrictionCurve> curves) const
  {
    for (auto& c : curves) {
      // The key names the points and the laws of every friction; a friction's fitted curve takes
      // the colour of its points, and the legend() its dash.
      const bool in_key = c.curve.style != CurveStyle::LinesBand || std::isnan(c.mu);
      c.curve.title = in_key ? labels[series] + ": " + c.curve.title : "";
      c.curve.line_type = line_type(c.mu);
      const bool open = c.curve.point_type == 6;                           // the source's numbers at the series' runs
      c.curve.point_type = series == 0 ? (open ? 6 : 7) : (open ? 4 : 5);  // circles, squares
      c.curve.dashed = series == 1;
      panel.curves.push_back(std::move(c.curve));
    }
  }
  // What a caption says of the styles, with or without fitted curves.
  std::string legend(bool with_curves = true) const
  {
    if (!with_curves) return labels[0] + ": circles; " + labels[1] + ": squares; a colour per friction";
    return labels[0] + ": circles, solid curves; " + labels[1] +
           ": squares, dashed curves; a colour per friction; bands: one standard error of the fitted curve (delta "
           "method, fit covariance)";
  }
};

// The fitted curves of one series over the extent of its points' x, if it has the fit.
using FittedCurves = std::function<std::vector<FrictionCurve>(size_t series, double x0, double x1)>;

// y against x of both series on one panel, each with its own fitted curves.
Panel overlaid(const SeriesComparison& comparison, const Styles& styles, const std::string& x, const std::string& y,
               const FittedCurves& fitted)
{
  Panel panel;
  for (size_t s = 0; s < 2; ++s) {
    auto points = points_by_friction(comparison.series[s], x, y);
    std::vector<Curve> drawn;
    for (const auto& p : points) drawn.push_back(p.curve);
    styles.add(panel, s, std::move(points));
    if (drawn.empty()) continue;
    auto [x0, x1] = x_extent(drawn);
    styles.add(panel, s, fitted(s, x0, x1));
  }
  return panel;
}

Panel titled(Panel panel, const std::string& title, const std::string& x_label, const std::string& y_label)
{
  panel.title = title;
  panel.x_label = x_label;
  panel.y_label = y_label;
  return panel;
}

// Panels in rows of `columns`, 700 x 650 px each (no panel: an empty figure, not drawn).
Figure grid(const std::string& name, const std::string& caption, std::vector<Panel> panels, size_t columns)
{
  columns = std::max<size_t>(columns, 1);
  const size_t rows = std::max<size_t>((panels.size() + columns - 1) / columns, 1);
  for (size_t i = 0; i < panels.size(); ++i) {
    panels[i].width = 1.0 / columns;
    panels[i].height = 1.0 / rows;
    panels[i].origin_x = static_cast<double>(i % columns) / columns;
    panels[i].origin_y = 1.0 - static_cast<double>(i / columns + 1) / rows;
  }
  return Figure{name, caption, panels, 700 * static_cast<int>(columns), 650 * static_cast<int>(rows)};
}

const DefinitionFits* fits_under(const SeriesAnalysis& series, const LayerDefinition& definition)
{
  for (const auto& fits : series.definitions)
    if (fits.definition.prefix == definition.prefix) return &fits;
  return nullptr;
}

// The definitions of h and phi that either series has fits under, surface first.
std::vector<LayerDefinition> definitions(const SeriesComparison& comparison)
{
  std::vector<LayerDefinition> found;
  for (const auto& definition : {kSurfaceDefinition, kPackingDefinition})
    if (fits_under(comparison.series[0], definition) || fits_under(comparison.series[1], definition))
      found.push_back(definition);
  return found;
}

// U against theta: a row per definition, Pouliquen's rule on the left, the mu(I) rule on the right.
Figure flow_rule_figure(const SeriesComparison& comparison, const Styles& styles)
{
  double u_max = 0, t0 = INFINITY, t1 = -INFINITY;
  for (const auto& series : comparison.series)
    for (const auto& run : series.runs) {
      u_max = std::max(u_max, run.value("U"));
      t0 = std::min(t0, run.entry.theta_deg), t1 = std::max(t1, run.entry.theta_deg);
    }
  const double top = 1.3 * u_max;  // the rules diverge at theta2
  using Rule = std::vector<FrictionCurve> (*)(const SeriesAnalysis&, const DefinitionFits&, double);
  const std::vector<std::pair<std::string, Rule>> rules = {{"Pouliquen's rule", pouliquen_curves},
                                                           {"the mu(I) rule", mu_of_i_curves}};
  std::vector<Panel> panels;
  for (const auto& definition : definitions(comparison))
    for (const auto& [rule_name, rule] : rules) {
      auto panel = overlaid(comparison, styles, "theta", "U", [&](size_t s, double, double) {
        const auto* fits = fits_under(comparison.series[s], definition);
        auto curves = fits ? rule(comparison.series[s], *fits, top) : std::vector<FrictionCurve>{};
        if (rule == pouliquen_curves)
          for (auto& source : source_velocity_points(comparison.series[s], definition.thickness))
            curves.push_back(std::move(source));
        return curves;
      });
      panel = titled(panel,
                     "U against tilt, " + rule_name + ", " + definition.name + " (curves at each series' mean " +
                         definition.thickness + " of each mu)",
                     "theta (deg)", "U / sqrt(g d)");
      panel.x_range = std::make_pair(t0 - 1, t1 + 1);
      panel.y_range = std::make_pair(0.0, top);
      panel.key = "bottom right";  // U rises with theta
      panels.push_back(panel);
    }
  return grid(
      "U_vs_theta",
      "U against theta with Pouliquen's (beta fixed) and the mu(I) rule of each series; " + styles.legend() +
          (comparison.series[0].source ? "; open symbols: the source's Pouliquen rule at each run's own theta and h"
                                       : ""),
      panels, 2);
}

// phi against U or I: a panel per definition, each series with its linear phi law.
Figure phi_figure(const SeriesComparison& comparison, const Styles& styles, bool against_velocity)
{
  std::vector<Panel> panels;
  for (const auto& definition : definitions(comparison)) {
    const std::string x = against_velocity ? "U" : definition.inertial;
    auto panel = overlaid(comparison, styles, x, definition.phi, [&](size_t s, double x0, double x1) {
      const auto* fits = fits_under(comparison.series[s], definition);
      if (!fits) return std::vector<FrictionCurve>{};
      const auto& law = against_velocity ? fits->phi_of_u : fits->phi_of_i;
      return law ? phi_law_curves(*law, x0, x1) : std::vector<FrictionCurve>{};
    });
    const auto& source = comparison.series[0].source;
    if (source && against_velocity && !panel.curves.empty()) {
      auto [u0, u1] = x_extent(panel.curves);
      for (auto& line : source_phi_lines(*source, u0, u1)) {
        line.curve.line_type = styles.line_type(line.mu);
        panel.curves.push_back(std::move(line.curve));
      }
    }
    panel = titled(panel, definition.phi + " against " + x + ", " + definition.name,
                   against_velocity ? "U / sqrt(g d)" : x, definition.phi);
    panel.key = "bottom left";  // phi falls as U and I rise
    panels.push_back(panel);
  }
  return grid(against_velocity ? "phi_vs_U" : "phi_vs_I",
              std::string("phi against ") + (against_velocity ? "U" : "I") +
                  " with each series' linear law, a panel per definition of h and phi; " + styles.legend() +
                  (comparison.series[0].source && against_velocity ? "; asterisks: the source's phi(U) law" : ""),
              panels, panels.size());
}

// f against x with each series' power law fitted over every friction.
Figure power_law_figure(const SeriesComparison& comparison, const Styles& styles, const std::string& name,
                        const std::string& x, const std::string& x_label, std::optional<PowerLaw> SeriesAnalysis::*law)
{
  auto panel = overlaid(comparison, styles, x, "f", [&](size_t s, double x0, double x1) {
    const auto& fitted = comparison.series[s].*law;
    if (!fitted) return std::vector<FrictionCurve>{};
    return std::vector<FrictionCurve>{{kEveryFriction, power_law_curve(*fitted, x0, x1)}};
  });
  if (const auto& source = comparison.series[0].source; source && !panel.curves.empty()) {
    auto [x0, x1] = x_extent(panel.curves);
    for (auto& line : source_frequency_range(*source, x0, x1)) panel.curves.push_back(std::move(line));
  }
  return grid(name,
              "Oscillation frequency f against " + x_label + " with each series' power law; " + styles.legend() +
                  (comparison.series[0].source ? "; dashed: the source's range of f" : ""),
              {titled(panel, "f against " + x_label, x_label, "f (Hz)")}, 1);
}

Figure amplitude_figure(const SeriesComparison& comparison, const Styles& styles)
{
  std::vector<Panel> panels;
  for (const auto& definition : definitions(comparison)) {
    auto panel = overlaid(comparison, styles, definition.phi, "A",
                          [](size_t, double, double) { return std::vector<FrictionCurve>{}; });
    panel = titled(panel, "A against " + definition.phi + ", " + definition.name, definition.phi, "A / sqrt(g d)");
    panel.key = "top right";  // A falls as phi rises
    panels.push_back(panel);
  }
  return grid("A_vs_phi", "Peak amplitude A against phi, a panel per definition of h and phi; " + styles.legend(false),
              panels, panels.size());
}

// theta against each reading of a run's I, a panel each, both series with the source's two rules.
Figure inertial_readings_figure(const SeriesComparison& comparison, const Styles& styles)
{
  std::vector<Panel> panels;
  const auto& source = comparison.series[0].source;
  for (const auto& definition : kInertialDefinitions) {
    auto panel = overlaid(comparison, styles, definition.result, "theta",
                          [](size_t, double, double) { return std::vector<FrictionCurve>{}; });
    if (panel.curves.empty() || !source) continue;
    auto [i0, i1] = x_extent(panel.curves);
    for (auto& rule : source_rule_curves(*source, 0.8 * i0, 1.2 * i1)) {
      rule.curve.line_type = styles.line_type(rule.mu);
      panel.curves.push_back(std::move(rule.curve));
    }
    panel =
        titled(panel, "theta against " + definition.result, definition.result + ": " + definition.name, "theta (deg)");
    panel.key = "bottom right";
    panels.push_back(panel);
  }
  return grid("flow_rules_by_I",
              "Each run's tilt against its I read three ways, with the source's Pouliquen (dashed) and mu(I) (solid) "
              "rules; " +
                  styles.legend(false),
              panels, panels.size());
}

std::vector<Figure> comparison_figures(const SeriesComparison& comparison)
{
  const Styles styles(comparison);
  return {flow_rule_figure(comparison, styles),
          inertial_readings_figure(comparison, styles),
          phi_figure(comparison, styles, true),
          phi_figure(comparison, styles, false),
          power_law_figure(comparison, styles, "f_vs_scale", "f_scale", "(sqrt(g d)/U g/d)^(1/2) (Hz)",
                           &SeriesAnalysis::f_vs_scale),
          power_law_figure(comparison, styles, "f_vs_shear_rate", "shear_rate", "U/h (1/s)",
                           &SeriesAnalysis::f_vs_shear_rate),
          amplitude_figure(comparison, styles)};
}

void write_compared_fits(const SeriesComparison& comparison, const std::vector<ComparedFit>& fits,
                         const std::string& path)
{
  auto out = open_output(path);
  out.precision(10);
  const auto& [a, b] = comparison.labels;
  out << "name,unit," << a << ',' << a << "_error," << b << ',' << b << "_error,difference_sigma\n";
  for (const auto& fit : fits) {
    out << fit.name << ',' << fit.unit;
    for (const auto& estimate : fit.estimates) {
      out << ',';
      if (estimate) out << estimate->value;
      out << ',';
      if (estimate && estimate->error) out << *estimate->error;
    }
    out << ',';
    if (fit.difference_sigma) out << *fit.difference_sigma;
    out << '\n';
  }
}

void fits_table(MarkdownReport& report, const SeriesComparison& comparison, const std::vector<ComparedFit>& fits)
{
  std::vector<std::vector<std::string>> rows;
  for (const auto& fit : fits) {
    std::vector<std::string> row{"`" + fit.name + "`"};
    for (const auto& e : fit.estimates) row.push_back(e ? format_estimate(e->value, e->error) : "–");
    char difference[32] = "–";
    if (fit.difference_sigma) std::snprintf(difference, sizeof difference, "%+.1f", *fit.difference_sigma);
    row.insert(row.end(), {difference, fit.unit});
    rows.push_back(row);
  }
  report.table({"fit", comparison.labels[0], comparison.labels[1], "difference (sigma)", "unit"}, rows);
}

std::string series_text(const SeriesComparison& comparison, size_t s)
{
  const auto& series = comparison.series[s];
  return comparison.labels[s] + ": `" + series.settings.manifest + "` (" + std::to_string(series.runs.size()) +
         " flowing runs, " + std::to_string(series.stopped.size()) + " stopped)";
}

}  // namespace

void write_comparison_outputs(SeriesComparison& comparison, const std::string& out_dir)
{
  const std::string figures_dir = out_dir + "/figures";
  std::filesystem::create_directories(figures_dir);
  const auto& labels = comparison.labels;
  MarkdownReport report("Series " + labels[0] + " against " + labels[1]);
  report.paragraph(series_text(comparison, 0) + "; " + series_text(comparison, 1) +
                   ". Each series is analysed exactly as `cdpost series` analyses it alone (its report gives the "
                   "method), with the same options. The difference is (" +
                   labels[1] + " - " + labels[0] +
                   ") in units of the combined error sqrt(sigma1^2 + sigma2^2), given where both fits have an "
                   "error; every row is in compared_fits.csv.");
  const auto fits = compared_fits(comparison);
  const std::vector<LabelledSeries> both{{labels[0], &comparison.series[0]}, {labels[1], &comparison.series[1]}};
  source_section(report, both);
  for (size_t i = 0; i < 2; ++i)
    solver_section(report, comparison.series[i], "Solver health of the runs of " + labels[i]);
  report.heading("Fits of both series");
  fits_table(report, comparison, fits);
  auto warnings = comparison_warnings(comparison);
  report.heading("Figures");
  for (const auto& figure : comparison_figures(comparison)) {
    if (figure.panels.empty()) continue;  // neither series has the quantities drawn
    if (auto problem = render_figure(figure, figures_dir)) warnings.push_back(*problem);
    else report.figure("figures", figure.name, figure.caption);
  }
  report.warnings(warnings);
  write_compared_fits(comparison, fits, out_dir + "/compared_fits.csv");
  write_source_comparison(both, out_dir + "/source_comparison.csv");
  report.write(out_dir + "/report.md");
}

}  // namespace cdpost
