// Figures, tables and the Markdown report of a series.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "analysis/creep_results.h"
#include "analysis/series_analysis.h"
#include "analysis/solver_health.h"
#include "figures/along_cell_series.h"
#include "figures/series_figures.h"
#include "io/ave_time.h"
#include "output/gnuplot.h"
#include "output/report.h"
#include "source/source_comparison.h"

namespace cdpost {

namespace {

std::string label(double value)
{
  return format_estimate(value, std::nullopt);
}

}  // namespace

std::vector<Curve> by_friction(const SeriesAnalysis& series, const std::string& x, const std::string& y)
{
  std::vector<Curve> curves;
  for (auto& points : points_by_friction(series, x, y)) curves.push_back(std::move(points.curve));
  return curves;
}

namespace {

Panel panel(const std::string& title, const std::string& x_label, const std::string& y_label, std::vector<Curve> curves)
{
  Panel p;
  p.title = title;
  p.x_label = x_label;
  p.y_label = y_label;
  p.curves = std::move(curves);
  return p;
}

// A fitted curve y(x) over [x0, x1] with its one-sigma band from the fit's covariance (delta
// method); `y` takes the fit's parameters. Points where the band is undefined, or the curve
// above y_max (a rule diverging at theta2), are left out.
Curve banded(const std::string& title, double x0, double x1, const FitResult& fit,
             const std::function<std::optional<double>(const std::vector<double>&, double)>& y, double y_max = INFINITY)
{
  Curve curve;
  curve.title = title;
  curve.style = CurveStyle::LinesBand;
  const auto parameters = fit.values();
  for (int i = 0; i <= 100; ++i) {
    const double x = x0 + (x1 - x0) * i / 100.0;
    const auto value = y(parameters, x);
    const auto sigma = propagated_error(fit, [&](const std::vector<double>& p) { return y(p, x); });
    if (!value || !sigma || *value > y_max) continue;
    curve.x.push_back(x);
    curve.y.push_back(*value);
    curve.y_error.push_back(*sigma);
  }
  return curve;
}

Figure power_law_figure(const SeriesAnalysis& series, const std::string& name, const std::string& x,
                        const std::string& x_label, const std::optional<PowerLaw>& law)
{
  auto curves = by_friction(series, x, "f");
  if (!curves.empty()) {
    auto [x0, x1] = x_extent(curves);
    if (law) curves.push_back(power_law_curve(*law, x0, x1));
    if (series.source)
      for (auto& line : source_frequency_range(*series.source, x0, x1)) curves.push_back(std::move(line));
  }
  return {name,
          "Oscillation frequency f against " + x_label + "; band: one standard error of the fitted law (delta method)" +
              (series.source ? "; dashed: the source's range of f" : ""),
          {panel("f against " + x_label, x_label, "f (Hz)", curves)}};
}

// phi against x (U or I) under one definition, with the fitted line of each friction and its band.
Panel phi_panel(const SeriesAnalysis& series, const DefinitionFits& fits, const std::string& x,
                const std::optional<PhiFit>& law, const std::string& x_label)
{
  auto curves = by_friction(series, x, fits.definition.phi);
  if (!curves.empty()) {
    auto [x0, x1] = x_extent(curves);
    if (law)
      for (auto& line : phi_law_curves(*law, x0, x1)) curves.push_back(std::move(line.curve));
    if (series.source && x == "U")
      for (auto& line : source_phi_lines(*series.source, x0, x1)) curves.push_back(std::move(line.curve));
  }
  auto p = panel(fits.definition.phi + " against " + x_label + ", " + fits.definition.name, x_label,
                 fits.definition.phi, curves);
  p.key = "bottom left";
  return p;
}

// Side by side, one panel per definition.
Figure definitions_figure(const std::string& name, const std::string& caption, std::vector<Panel> panels)
{
  for (size_t i = 0; i < panels.size(); ++i) {
    panels[i].width = 1.0 / panels.size();
    panels[i].origin_x = static_cast<double>(i) / panels.size();
  }
  return Figure{name, caption, panels, 700 * static_cast<int>(panels.size()), 650};
}

std::vector<Figure> phi_figures(const SeriesAnalysis& series)
{
  std::vector<Panel> against_u, against_i;
  for (const auto& fits : series.definitions) {
    against_u.push_back(phi_panel(series, fits, "U", fits.phi_of_u, "U / sqrt(g d)"));
    against_i.push_back(phi_panel(series, fits, fits.definition.inertial, fits.phi_of_i, fits.definition.inertial));
  }
  const std::string band = "; bands: one standard error of the fitted line (delta method, fit covariance)";
  const std::string source = series.source ? "; dashed: the source's phi(U) law" : "";
  return {definitions_figure(
              "phi_vs_U", "phi against U with the linear law, per definition of h and phi" + band + source, against_u),
          definitions_figure("phi_vs_I", "phi against I with the linear law, per definition of h and phi" + band,
                             against_i)};
}

// Mean h (in d, result `thickness`) of the runs of one friction: the flow-rule curves are drawn for it.
double mean_thickness(const SeriesAnalysis& series, double mu, const std::string& thickness)
{
  double sum = 0;
  int count = 0;
  for (const auto& run : series.runs)
    if (run.entry.mu == mu && run.estimate(thickness)) sum += run.value(thickness), ++count;
  return count ? sum / count : 0;
}

double tan_deg(double deg)
{
  return std::tan(deg * M_PI / 180);
}

// U/sqrt(g d) = I (h/d)^1.5 of a rule's I(tan θ), none where the rule gives none.
std::optional<double> velocity(std::optional<double> inertial, double h)
{
  if (!inertial || !(*inertial > 0)) return std::nullopt;
  return *inertial * std::pow(h, 1.5);
}

Panel flow_rule_panel(const SeriesAnalysis& series, const DefinitionFits& fits)
{
  auto curves = by_friction(series, "theta", "U");
  auto [t0, t1] = x_extent(curves);
  double u_max = 0;
  for (const auto& c : curves) u_max = std::max(u_max, *std::max_element(c.y.begin(), c.y.end()));
  const double top = 1.3 * u_max;  // the rules diverge at theta2
  for (auto* rule : {pouliquen_curves, mu_of_i_curves})
    for (auto& fitted : rule(series, fits, top)) curves.push_back(std::move(fitted.curve));
  for (auto& source : source_velocity_points(series, fits.definition.thickness))
    curves.push_back(std::move(source.curve));
  auto p = panel(
      "U against tilt, " + fits.definition.name + " (curves at the mean " + fits.definition.thickness + " of each mu)",
      "theta (deg)", "U / sqrt(g d)", curves);
  p.x_range = std::make_pair(t0 - 1, t1 + 1);
  p.y_range = std::make_pair(0.0, top);
  return p;
}

Figure flow_rule_figure(const SeriesAnalysis& series)
{
  std::vector<Panel> panels;
  for (const auto& fits : series.definitions) panels.push_back(flow_rule_panel(series, fits));
  return definitions_figure(
      "U_vs_theta",
      "U against theta with Pouliquen's and the mu(I) rule, per definition of h and phi; bands: one "
      "standard error of the fitted curve (delta method, fit covariance)" +
          std::string(series.source ? "; open circles: the source's Pouliquen rule at each run's own theta and h" : ""),
      panels);
}

// theta against each reading of a run's I (source/source_numbers.h), one panel each, with both
// of the source's rules over the runs' range of I.
std::optional<Figure> inertial_readings_figure(const SeriesAnalysis& series)
{
  if (!series.source) return std::nullopt;
  std::vector<Panel> panels;
  for (const auto& definition : kInertialDefinitions) {
    auto points = points_by_friction(series, definition.result, "theta");
    if (points.empty()) continue;
    std::vector<Curve> curves;
    auto colour = [&](double mu) {  // a friction's points and the source's rules at it: one colour
      auto found = std::find_if(points.begin(), points.end(), [&](const FrictionCurve& c) { return c.mu == mu; });
      return 1 + static_cast<int>(found - points.begin());
    };
    for (auto& p : points) {
      p.curve.line_type = colour(p.mu);
      curves.push_back(p.curve);
    }
    auto [i0, i1] = x_extent(curves);
    for (auto& rule : source_rule_curves(*series.source, 0.8 * i0, 1.2 * i1)) {
      rule.curve.line_type = colour(rule.mu);
      curves.push_back(std::move(rule.curve));
    }
    auto p =
        panel("theta against " + definition.result, definition.result + ": " + definition.name, "theta (deg)", curves);
    p.key = "bottom right";
    panels.push_back(p);
  }
  if (panels.empty()) return std::nullopt;
  return definitions_figure("flow_rules_by_I",
                            "Each run's tilt against its I read three ways, with the source's Pouliquen (dashed) and "
                            "mu(I) (solid) rules",
                            panels);
}

std::optional<Figure> length_figure(const SeriesAnalysis& series)
{
  std::vector<std::pair<std::string, std::string>> quantities = {
      {"f", "f (Hz)"}, {"A", "A / sqrt(g d)"}, {"A_mean", "A_mean / sqrt(g d)"}};
  Figure figure{"L_series", "f, A and A_mean against the cell length L", {}, 900, 1000};
  for (size_t q = 0; q < quantities.size(); ++q) {
    Curve curve;
    curve.style = CurveStyle::ErrorBars;
    for (const auto& run : series.runs)
      if (run.entry.length_d) {
        auto e = *run.estimate(quantities[q].first);
        curve.x.push_back(*run.entry.length_d);
        curve.y.push_back(e.value);
        curve.y_error.push_back(e.error.value_or(0));
      }
    if (curve.x.size() < 2) return std::nullopt;
    auto p = panel(quantities[q].first + " against L", "L / d", quantities[q].second, {curve});
    p.key = "off";
    p.height = 1.0 / 3;
    p.origin_y = 1.0 - (q + 1) / 3.0;
    figure.panels.push_back(p);
  }
  return figure;
}

// A run's label in figures and tables: its manifest name, friction and tilt.
std::string run_label(const ManifestEntry& entry)
{
  return entry.name + " (mu " + label(entry.mu) + ", " + label(entry.theta_deg) + " deg)";
}

std::optional<Figure> depth_figure(const SeriesAnalysis& series)
{
  std::vector<Curve> curves;
  for (const auto& run : series.runs) {
    Curve curve;
    curve.title = run_label(run.entry);
    curve.style = CurveStyle::LinesPoints;
    for (const auto& layer : run.analysis.layers)
      if (layer.amplitude_at_f > 0) {  // the axis is logarithmic
        curve.x.push_back(layer.z_d);
        curve.y.push_back(layer.amplitude_at_f);
      }
    if (!curve.x.empty()) curves.push_back(curve);
  }
  if (curves.empty()) return std::nullopt;
  auto p = panel("Amplitude at each run's f by layer", "z / d (layer centre)", "amplitude at f / sqrt(g d)", curves);
  p.log_y = true;
  p.key = "outside right top";
  return Figure{"amplitude_vs_depth",
                "Amplitude of v at the run's peak frequency f in each layer, one curve per run",
                {p},
                1200,
                650};
}

// h_stop against theta (stopped runs, fitted h_stop(theta)) and Fr = U/sqrt(g h) against
// h/h_stop(theta) (flowing runs, Fr = beta h/h_stop): the evidence of each beta fitted.
std::optional<Figure> beta_free_figure(const SeriesAnalysis& series)
{
  std::vector<Curve> stops, froude;
  double h_max = 0;
  for (const auto& entry : series.stopped) h_max = std::max(h_max, *entry.h_stop_d);
  for (const auto& fit : series.pouliquen_free) {
    if (!fit.beta) continue;
    const double mu = fit.angles.mu, tan1 = fit.raw["tan_theta1"].value, tan2 = fit.raw["tan_theta2"].value,
                 ell = fit.ell->value;
    Curve measured, flowing;
    measured.title = "stopped runs, mu = " + label(mu);
    flowing.title = "flowing runs, mu = " + label(mu);
    for (const auto& entry : series.stopped)
      if (entry.mu == mu) measured.x.push_back(entry.theta_deg), measured.y.push_back(*entry.h_stop_d);
    auto h_stop = [&](double theta) { return pouliquen_stop_thickness(std::tan(theta * M_PI / 180), tan1, tan2, ell); };
    for (const auto& run : series.runs)
      if (auto hs = h_stop(run.entry.theta_deg); run.entry.mu == mu && hs && run.estimate("h")) {
        const double h = run.value("h");
        flowing.x.push_back(h / *hs);
        flowing.y.push_back(run.value("U") / std::sqrt(h));
      }
    stops.push_back(measured);
    stops.push_back(banded(
        "h_stop(theta), mu = " + label(mu), fit.angles.theta1_deg.value, fit.angles.theta2_deg.value, fit.raw,
        [](const std::vector<double>& p, double theta) {
          return pouliquen_stop_thickness(std::tan(theta * M_PI / 180), p[0], p[1], p[2]);
        },
        2 * h_max));
    froude.push_back(flowing);
    if (!flowing.x.empty())
      froude.push_back(banded("Fr = beta h/h_stop, beta = " + format_estimate(fit.beta->value, fit.beta->error), 0,
                              *std::max_element(flowing.x.begin(), flowing.x.end()), fit.raw,
                              [](const std::vector<double>& p, double x) { return std::optional<double>(p[3] * x); }));
  }
  if (stops.empty()) return std::nullopt;
  auto left = panel("Deposit thickness of the stopped runs", "theta (deg)", "h_stop / d", stops);
  left.y_range = std::make_pair(0.0, 2 * h_max);  // h_stop(theta) diverges at theta1
  left.width = 0.5;
  auto right = panel("Froude number of the flowing runs", "h / h_stop(theta)", "Fr = U / sqrt(g h)", froude);
  right.width = 0.5;
  right.origin_x = 0.5;
  return Figure{"pouliquen_beta_free",
                "Pouliquen's rule with beta free: h_stop(theta) and Fr = beta h/h_stop; bands: one standard error "
                "(delta method)",
                {left, right},
                1300,
                600};
}

std::vector<Figure> series_figures(const SeriesAnalysis& series)
{
  std::vector<Figure> figures{
      power_law_figure(series, "f_vs_scale", "f_scale", "(sqrt(g d)/U g/d)^(1/2) (Hz)", series.f_vs_scale),
      power_law_figure(series, "f_vs_shear_rate", "shear_rate", "U/h (1/s)", series.f_vs_shear_rate),
      {"A_vs_U",
       "Peak amplitude A against U",
       {panel("A against U", "U / sqrt(g d)", "A / sqrt(g d)", by_friction(series, "U", "A"))}},
      {"A_vs_phi",
       "Peak amplitude A against phi",
       {panel("A against phi", "phi", "A / sqrt(g d)", by_friction(series, "phi", "A"))}},
      flow_rule_figure(series)};
  for (auto& figure : phi_figures(series)) figures.push_back(figure);
  if (auto readings = inertial_readings_figure(series)) figures.push_back(*readings);
  if (auto lengths = length_figure(series)) figures.push_back(*lengths);
  if (auto depth = depth_figure(series)) figures.push_back(*depth);
  if (auto beta = beta_free_figure(series)) figures.push_back(*beta);
  return figures;
}

void write_runs_table(const SeriesAnalysis& series, const std::string& path)
{
  const std::vector<std::string> names = {"U",
                                          "phi",
                                          "h",
                                          "I",
                                          "I_bagnold",
                                          "I_local",
                                          "shear_rate_local",
                                          "pressure_local",
                                          "phi_local",
                                          "phi_bulk",
                                          "h_packing",
                                          "I_packing",
                                          "shear_rate",
                                          "f_scale",
                                          "f",
                                          "A",
                                          "A_mean",
                                          "creep_lambda",
                                          "creep_lambda_first_decade",
                                          "creep_z_high",
                                          "creep_z_low",
                                          "creep_points",
                                          "creep_floor",
                                          "solver_steps",
                                          "solver_unconverged_steps",
                                          "solver_unconverged_fraction",
                                          "solver_sweeps_median",
                                          "solver_sweeps_p99",
                                          "solver_overlap_max"};
  auto out = open_output(path);
  out.precision(10);
  out << "run,mu,theta_deg,L_d";
  for (const auto& n : names) out << ',' << n << ',' << n << "_error";
  out << '\n';
  for (const auto& run : series.runs) {
    out << run.entry.name << ',' << run.entry.mu << ',' << run.entry.theta_deg << ',';
    if (run.entry.length_d) out << *run.entry.length_d;
    for (const auto& n : names) {
      auto e = run.estimate(n);
      out << ',';
      if (e) out << e->value;
      out << ',';
      if (e && e->error) out << *e->error;
    }
    out << '\n';
  }
}

// One CSV row per residual: run, mu, theta, fit, quantity, observed − fitted.
void write_residuals(const SeriesAnalysis& series, const std::string& path)
{
  auto out = open_output(path);
  out.precision(10);
  out << "run,mu,theta_deg,fit,quantity,residual\n";
  for (const auto& r : series.residuals)
    out << r.run << ',' << r.mu << ',' << r.theta_deg << ',' << r.fit << ',' << r.quantity << ',' << r.value << '\n';
}

// One row per held value and friction: the angles refitted and the rms residual.
void write_held_fits(const SeriesAnalysis& series, const std::string& path)
{
  auto out = open_output(path);
  out.precision(10);
  out << "definition,rule,held_parameter,held_value,mu,theta1_deg,theta1_error_deg,theta2_deg,theta2_error_deg,"
         "rms_residual_tan_theta,dof\n";
  for (const auto& h : series.held_fits) {
    out << (h.definition.empty() ? "surface" : "packing") << ',' << h.rule << ',' << (h.rule == "muI" ? "I0" : "ell")
        << ',' << h.held << ',' << h.angles.mu;
    for (const auto* angle : {&h.angles.theta1_deg, &h.angles.theta2_deg}) {
      out << ',' << angle->value << ',';
      if (angle->error) out << *angle->error;
    }
    out << ',' << h.rms_residual << ',' << h.dof << '\n';
  }
}

// The held fits of one rule and definition as a table: a row per held value, the rms and each
// friction's θ1, θ2; the free fit's value and rms head the caption.
void held_table(MarkdownReport& report, const SeriesAnalysis& series, const std::string& definition,
                const std::string& rule)
{
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> header{rule == "muI" ? "I0 held" : "l held", "mu", "theta1 (deg)", "theta2 (deg)",
                                  "rms residual (tan theta)"};
  for (const auto& h : series.held_fits)
    if (h.definition == definition && h.rule == rule)
      rows.push_back({label(h.held), label(h.angles.mu),
                      format_estimate(h.angles.theta1_deg.value, h.angles.theta1_deg.error),
                      format_estimate(h.angles.theta2_deg.value, h.angles.theta2_deg.error),
                      format_estimate(h.rms_residual, std::nullopt)});
  if (rows.empty()) return;
  std::vector<std::string> fitted;  // the free fit's parameter and rms residual
  for (const std::string& stem : rule == "muI"
                                     ? std::vector<std::string>{"muI_I0", "muI_rms_residual"}
                                     : std::vector<std::string>{"pouliquen_ell_mu", "pouliquen_rms_residual_mu"})
    for (const auto& row : series.fits.rows())
      if (row.name.rfind(definition + stem, 0) == 0)
        fitted.push_back(row.name + " = " + format_estimate(row.value, row.error));
  report.paragraph((definition.empty() ? "Surface definition" : "Packing definition") + std::string(", ") +
                   (rule == "muI" ? "the mu(I) rule with I0 held (one joint fit per value, the rms over every run)"
                                  : "Pouliquen's rule with l held (beta = " + label(series.settings.beta) +
                                        ", one fit per friction and value)") +
                   ". Free fit: " + join_names(fitted) + ".");
  report.table(header, rows);
}

// One row per run and layer: the amplitude at the run's f against the layer's z.
void write_layer_amplitudes(const SeriesAnalysis& series, const std::string& path)
{
  auto out = open_output(path);
  out.precision(10);
  out << "run,mu,theta_deg,z_d,amplitude_at_f\n";
  for (const auto& run : series.runs)
    for (const auto& layer : run.analysis.layers)
      out << run.entry.name << ',' << run.entry.mu << ',' << run.entry.theta_deg << ',' << layer.z_d << ','
          << layer.amplitude_at_f << '\n';
}

// One row per run whose decay length could be fitted (the others are warnings).
void write_depth_decay(const SeriesAnalysis& series, const std::string& path)
{
  auto out = open_output(path);
  out.precision(10);
  out << "run,mu,theta_deg,decay_length_d,decay_length_error_d,layers,log_rms_residual\n";
  for (const auto& run : series.runs)
    if (const auto& decay = run.depth_decay)
      out << run.entry.name << ',' << run.entry.mu << ',' << run.entry.theta_deg << ',' << decay->lambda.value << ','
          << *decay->lambda.error << ',' << decay->layers << ',' << decay->log_rms_residual << '\n';
}

// Per run (flowing, then stopped), the residual of each flow-rule fit; empty where a fit left the run out.
void residual_table(MarkdownReport& report, const SeriesAnalysis& series)
{
  std::vector<std::string> fits;
  for (const auto& r : series.residuals)
    if (std::find(fits.begin(), fits.end(), r.fit) == fits.end()) fits.push_back(r.fit);
  if (fits.empty()) return;
  std::vector<const ManifestEntry*> entries;
  for (const auto& run : series.runs) entries.push_back(&run.entry);
  for (const auto& entry : series.stopped) entries.push_back(&entry);
  std::vector<std::vector<std::string>> rows;
  for (const auto* entry : entries) {
    std::vector<std::string> row{run_label(*entry) + (entry->stopped ? ", stopped" : "")};
    for (const auto& fit : fits) {
      auto found = std::find_if(series.residuals.begin(), series.residuals.end(),
                                [&](const SeriesResidual& r) { return r.run == entry->name && r.fit == fit; });
      row.push_back(found == series.residuals.end() ? "" : format_estimate(found->value, std::nullopt));
    }
    rows.push_back(row);
  }
  std::vector<std::string> header{"run"};
  for (const auto& fit : fits)
    header.push_back(fit + (fit.find("phi_") != std::string::npos ? " (phi)" : " (tan theta)"));
  report.table(header, rows);
}

void depth_table(MarkdownReport& report, const SeriesAnalysis& series)
{
  std::vector<std::vector<std::string>> rows;
  for (const auto& run : series.runs)
    if (const auto& decay = run.depth_decay)
      rows.push_back({run_label(run.entry), format_estimate(decay->lambda.value, decay->lambda.error),
                      std::to_string(decay->layers), format_estimate(decay->log_rms_residual, std::nullopt)});
  if (rows.empty()) report.paragraph("No run has a decay length (see the warnings).");
  else report.table({"run", "decay length lambda (d)", "layers fitted", "rms of ln a about the fit"}, rows);
}

// The creep measure's cells of one run from its results (fit/creep.h): lambda, its fit range,
// the range's bins, the floor and the local decay lengths; or why there is no lambda.
std::vector<std::string> creep_cells(const SeriesRun& run)
{
  const auto lambda = run.estimate("creep_lambda"), floor = run.estimate("creep_floor");
  const auto points = run.estimate("creep_points"), low = run.estimate("creep_z_low"),
             high = run.estimate("creep_z_high");
  auto plain = [](const std::optional<Estimate>& e) { return e ? format_estimate(e->value, std::nullopt) : ""; };
  std::string measured = lambda ? format_estimate(lambda->value, lambda->error) : "";
  if (!floor) measured = lambda ? measured + " (whole-bed fit: results without the range)" : "unresolved: no floor";
  else if (!lambda)
    measured = "unresolved: " + plain(points) + " bins above " + plain(Estimate{kFloorMultiple, {}}) + " x the floor";
  std::string bands;
  for (const auto& row : run.analysis.results.rows())
    if (auto band = creep_band_of(row.name))
      bands += (bands.empty() ? "" : "; ") + *band + ": " + format_estimate(row.value, row.error);
  char floor_text[32] = "";  // two digits: a noise level
  if (floor) std::snprintf(floor_text, sizeof floor_text, "%.2g", floor->value);
  return {run_label(run.entry), measured,   low && high ? plain(low) + " to " + plain(high) : "",
          plain(points),        floor_text, bands};
}

void creep_table(MarkdownReport& report, const SeriesAnalysis& series)
{
  std::vector<std::vector<std::string>> rows;
  for (const auto& run : series.runs) rows.push_back(creep_cells(run));
  report.table({"run", "creep length lambda (d)", "fit range z (d)", "bins", "floor (sqrt(g d))",
                "local decay length by depth below the wall tops (d)"},
               rows);
}

}  // namespace

void solver_section(MarkdownReport& report, const SeriesAnalysis& series, const std::string& heading)
{
  report.heading(heading);
  report.paragraph(
      "From each run's solver.time (each row the means over one solver_interval): the steps whose last solve hit the "
      "sweep cap, the median and 99th percentile of the rows' sweeps per step, the largest row mean of the steps' "
      "largest interpenetration; each run's report lists the fix's solver lines of its log. Per run: solver_* in "
      "runs.csv.");
  std::vector<std::vector<std::string>> rows;
  for (const auto& run : series.runs) {
    auto cell = [&](const std::string& name, double scale = 1) {
      const auto e = run.estimate(name);
      return e ? format_estimate(scale * e->value, std::nullopt) : std::string("not recorded");
    };
    const bool recorded = run.estimate("solver_unconverged_steps") && run.estimate("solver_steps");
    rows.push_back({run_label(run.entry),
                    recorded ? count_text(run.estimate("solver_unconverged_steps")->value) + " of " +
                                   count_text(run.estimate("solver_steps")->value)
                             : "not recorded",
                    cell("solver_unconverged_fraction", 100), cell("solver_sweeps_median"), cell("solver_sweeps_p99"),
                    cell("solver_overlap_max")});
  }
  report.table({"run", "unconverged steps", "unconverged (%)", "sweeps per step, median", "99th percentile",
                "largest interpenetration (d)"},
               rows);
}

std::vector<FrictionCurve> points_by_friction(const SeriesAnalysis& series, const std::string& x, const std::string& y)
{
  std::set<double> mus;
  for (const auto& run : series.runs) mus.insert(run.entry.mu);
  std::vector<FrictionCurve> curves;
  for (double mu : mus) {
    Curve curve;
    curve.title = "mu = " + label(mu);
    curve.style = CurveStyle::ErrorBars;
    auto value = [](const SeriesRun& run, const std::string& name) {
      return name == "theta" ? std::optional<Estimate>(Estimate{run.entry.theta_deg, {}}) : run.estimate(name);
    };
    for (const auto& run : series.runs) {
      auto xv = value(run, x), yv = value(run, y);
      if (run.entry.mu != mu || !xv || !yv) continue;
      curve.x.push_back(xv->value);
      curve.y.push_back(yv->value);
      curve.y_error.push_back(yv->error.value_or(0));
    }
    if (!curve.x.empty()) curves.push_back({mu, curve});
  }
  return curves;
}

std::vector<FrictionCurve> pouliquen_curves(const SeriesAnalysis& series, const DefinitionFits& fits, double u_max)
{
  std::vector<FrictionCurve> curves;
  const double beta = series.settings.beta;
  for (const auto& fit : fits.pouliquen) {
    const double h = mean_thickness(series, fit.angles.mu, fits.definition.thickness);
    curves.push_back({fit.angles.mu, banded(
                                         "Pouliquen, mu = " + label(fit.angles.mu), fit.angles.theta1_deg.value,
                                         fit.angles.theta2_deg.value, fit.raw,
                                         [=](const std::vector<double>& p, double theta) {
                                           auto h_stop = pouliquen_stop_thickness(tan_deg(theta), p[0], p[1], p[2]);
                                           return velocity(
                                               h_stop ? std::optional<double>(beta / *h_stop) : std::nullopt, h);
                                         },
                                         u_max)});
  }
  return curves;
}

std::vector<FrictionCurve> mu_of_i_curves(const SeriesAnalysis& series, const DefinitionFits& fits, double u_max)
{
  std::vector<FrictionCurve> curves;
  if (!fits.mu_of_i) return curves;
  for (size_t m = 0; m < fits.mu_of_i->angles.size(); ++m) {
    const auto& angles = fits.mu_of_i->angles[m];
    const double h = mean_thickness(series, angles.mu, fits.definition.thickness);
    curves.push_back({angles.mu, banded(
                                     "mu(I), mu = " + label(angles.mu), angles.theta1_deg.value,
                                     angles.theta2_deg.value, fits.mu_of_i->raw,
                                     [=](const std::vector<double>& p, double theta) {
                                       const double t = tan_deg(theta), tan1 = p[1 + 2 * m], tan2 = p[2 + 2 * m];
                                       if (!(t > tan1 && t < tan2)) return std::optional<double>();
                                       return velocity(p[0] * (t - tan1) / (tan2 - t), h);
                                     },
                                     u_max)});
  }
  return curves;
}

std::vector<FrictionCurve> phi_law_curves(const PhiFit& law, double x0, double x1)
{
  std::vector<FrictionCurve> curves;
  const auto slope = static_cast<size_t>(law.raw.parameters.size() - 1);
  for (size_t m = 0; m < law.phi_c.size(); ++m)
    curves.push_back(
        {law.phi_c[m].first, banded("phi_c - k x, mu = " + label(law.phi_c[m].first), x0, x1, law.raw,
                                    [=](const std::vector<double>& p, double xv) { return p[m] - p[slope] * xv; })});
  return curves;
}

Curve power_law_curve(const PowerLaw& law, double x0, double x1)
{
  return banded("f = " + format_estimate(law.prefactor.value, law.prefactor.error) + " x^(" +
                    format_estimate(law.exponent.value, law.exponent.error) + ")",
                x0, x1, law.line,
                [](const std::vector<double>& p, double xv) { return std::exp(p[0]) * std::pow(xv, p[1]); });
}

std::pair<double, double> x_extent(const std::vector<Curve>& curves)
{
  double low = INFINITY, high = -INFINITY;
  for (const auto& c : curves)
    for (double x : c.x) low = std::min(low, x), high = std::max(high, x);
  return {low, high};
}

void write_series_outputs(SeriesAnalysis& series, const std::string& out_dir)
{
  const std::string figures_dir = out_dir + "/figures";
  std::filesystem::create_directories(figures_dir);
  MarkdownReport report("Series " + series.settings.manifest);
  report.paragraph(
      std::to_string(series.runs.size()) +
      " flowing runs, each analysed as by `cdpost run` (see its report for the method), and " +
      std::to_string(series.stopped.size()) +
      " stopped runs (manifest: stopped = 1, deposit thickness h_stop; not analysed). Fits by GSL least squares; "
      "errors are one sigma from the covariance scaled by the residual variance. Pouliquen's rule with beta = " +
      label(series.settings.beta) +
      " (`pouliquen_*`) and with beta free (`pouliquen_betafree_*`): the flowing runs depend on beta and l only "
      "through "
      "l/beta, so beta and l are given separately only for a friction with stopped runs, whose h_stop(theta) fixes l. "
      "Correlations are Pearson's r with the number of runs n and the two-sided p-value of r (Student t, n - 2 degrees "
      "of freedom); over all runs and, when the series has several frictions, per mu (`_mu<mu>`). Per-run numbers: "
      "runs.csv.");
  report.paragraph(
      "Two definitions of the layer's thickness and packing (doc/scene.md): the surface one, h = 2 <z> over the grains "
      "above the wall tops and phi = their area/(L h), gives the fits without prefix; the packing one, phi_bulk = the "
      "mean of phi(z) over 0.2 h-0.8 h and h_packing = the height where phi(z) falls to half phi_bulk (I_packing = U/"
      "h_packing^1.5), gives those named `packing_*`. Under each, phi = phi_c(mu) - k_I I is fitted too (`phiI_*`). "
      "The "
      "fitted curves of the figures carry one-standard-error bands from the fit's covariance (delta method: var y = "
      "g^T C g, g the curve's gradient in the parameters).");
  solver_section(report, series, "Solver health of the runs");
  report.heading("Fitted numbers");
  report.table(series.fits);
  report.heading("Residuals of the flow-rule fits");
  report.paragraph(
      "Observed minus fitted, in tan theta for the flow rules and in phi for phi(U); the rms of each fit is in the "
      "table "
      "above (`*_rms_residual*`); every residual is in residuals.csv.");
  residual_table(report, series);
  report.heading("What the flow-rule fits determine");
  report.paragraph(
      "Over the runs' range of I the mu(I) rule's I0 and theta2 trade off, and so do Pouliquen's theta2 and l: "
      "`*_corr_I0_theta2_mu<mu>` and `*_corr_theta2_ell_mu<mu>` above are their correlation coefficients "
      "cov/(sigma sigma) from the fit's covariance. Below, each rule refitted with that parameter held at several "
      "values, the others free (held_fits.csv): where the rms residual hardly changes, the runs do not determine the "
      "held parameter.");
  for (const auto& fits : series.definitions)
    for (const std::string rule : {"muI", "pouliquen"}) held_table(report, series, fits.definition.prefix, rule);
  report.heading("Decay of the oscillation with depth");
  report.paragraph(
      "The amplitude of v at each run's f per layer (layer_amplitudes.csv, figure amplitude_vs_depth), fitted as "
      "a = a_s exp(z/lambda) over the layers lying wholly in the flowing layer 0 <= z <= h (the bed is left out); "
      "given "
      "only when at least 3 layers qualify and 1/lambda exceeds twice its error (depth_decay.csv). A layer at the "
      "noise "
      "floor flattens the profile; the rms of ln a shows how far the profile is from one exponential.");
  depth_table(report, series);
  report.heading("Creep below the wall tops");
  report.paragraph(
      "Each run's u(z) below the wall tops fitted as u0 exp(z/lambda) over the bins from the wall tops down to where u "
      "first falls below 10 x the noise floor of the bed (estimated from the deep bed where u stops decaying, or given "
      "by --creep-floor), with the local decay length over 3 d bands of that range (doc/postproc.md, The creep "
      "measure); fewer than 4 bins give no lambda. Per run: creep_lambda, creep_z_high, creep_z_low, creep_points and "
      "creep_floor in runs.csv.");
  creep_table(report, series);
  along_cell_section(series, report, out_dir);
  source_section(report, {{"ours", &series}});
  inertial_readings_section(report, series);
  report.heading("Figures");
  for (const auto& figure : series_figures(series)) {
    if (auto problem = render_figure(figure, figures_dir)) series.warnings.push_back(*problem);
    else report.figure("figures", figure.name, figure.caption);
  }
  report.warnings(series.warnings);
  write_runs_table(series, out_dir + "/runs.csv");
  write_residuals(series, out_dir + "/residuals.csv");
  write_held_fits(series, out_dir + "/held_fits.csv");
  write_layer_amplitudes(series, out_dir + "/layer_amplitudes.csv");
  write_depth_decay(series, out_dir + "/depth_decay.csv");
  write_source_comparison({{"ours", &series}}, out_dir + "/source_comparison.csv");
  write_inertial_readings(series, out_dir + "/inertial_readings.csv");
  series.fits.write_csv(out_dir + "/fits.csv");
  series.fits.write_json(out_dir + "/fits.json", series.warnings);
  report.write(out_dir + "/report.md");
}

}  // namespace cdpost
