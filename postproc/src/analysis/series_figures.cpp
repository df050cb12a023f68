// Figures, tables and the Markdown report of a series.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "analysis/series_analysis.h"
#include "output/gnuplot.h"
#include "output/report.h"

namespace cdpost {

namespace {

std::string label(double value) { return format_estimate(value, std::nullopt); }

// One curve per friction coefficient of result y (with its error bars if any) against x.
std::vector<Curve> by_friction(const SeriesAnalysis& series, const std::string& x, const std::string& y) {
  std::set<double> mus;
  for (const auto& run : series.runs) mus.insert(run.entry.mu);
  std::vector<Curve> curves;
  for (double mu : mus) {
    Curve curve;
    curve.title = "mu = " + label(mu);
    curve.style = CurveStyle::ErrorBars;
    for (const auto& run : series.runs) {
      auto xv = x == "theta" ? std::optional<Estimate>(Estimate{run.entry.theta_deg, {}}) : run.estimate(x);
      auto yv = run.estimate(y);
      if (run.entry.mu != mu || !xv || !yv) continue;
      curve.x.push_back(xv->value);
      curve.y.push_back(yv->value);
      curve.y_error.push_back(yv->error.value_or(0));
    }
    if (!curve.x.empty()) curves.push_back(curve);
  }
  return curves;
}

Panel panel(const std::string& title, const std::string& x_label, const std::string& y_label, std::vector<Curve> curves) {
  Panel p;
  p.title = title;
  p.x_label = x_label;
  p.y_label = y_label;
  p.curves = std::move(curves);
  return p;
}

Curve sampled(const std::string& title, double x0, double x1, const std::function<std::optional<double>(double)>& y) {
  Curve curve;
  curve.title = title;
  curve.style = CurveStyle::Lines;
  for (int i = 0; i <= 100; ++i) {
    double x = x0 + (x1 - x0) * i / 100.0;
    if (auto value = y(x)) {
      curve.x.push_back(x);
      curve.y.push_back(*value);
    }
  }
  return curve;
}

std::pair<double, double> x_extent(const std::vector<Curve>& curves) {
  double low = INFINITY, high = -INFINITY;
  for (const auto& c : curves)
    for (double x : c.x) low = std::min(low, x), high = std::max(high, x);
  return {low, high};
}

Figure power_law_figure(const SeriesAnalysis& series, const std::string& name, const std::string& x, const std::string& x_label,
                        const std::optional<PowerLaw>& law) {
  auto curves = by_friction(series, x, "f");
  if (law && !curves.empty()) {
    auto [x0, x1] = x_extent(curves);
    curves.push_back(sampled("f = " + format_estimate(law->prefactor.value, law->prefactor.error) + " x^(" +
                                 format_estimate(law->exponent.value, law->exponent.error) + ")",
                             x0, x1, [&](double xv) { return law->prefactor.value * std::pow(xv, law->exponent.value); }));
  }
  return {name, "Oscillation frequency f against " + x_label, {panel("f against " + x_label, x_label, "f (Hz)", curves)}};
}

Figure phi_figure(const SeriesAnalysis& series) {
  auto curves = by_friction(series, "U", "phi");
  if (series.phi_of_u && !curves.empty()) {
    auto [u0, u1] = x_extent(curves);
    for (const auto& [mu, phi_c] : series.phi_of_u->phi_c) {
      const double k = series.phi_of_u->k.value, c = phi_c.value;
      curves.push_back(sampled("phi_c - k U, mu = " + label(mu), u0, u1, [=](double u) { return c - k * u; }));
    }
  }
  return {"phi_vs_U", "phi against U with the linear law", {panel("Area fraction against velocity", "U / sqrt(g d)", "phi", curves)}};
}

// Mean h (in d) of the runs of one friction coefficient: the flow-rule curves are drawn for it.
double mean_thickness(const SeriesAnalysis& series, double mu) {
  double sum = 0;
  int count = 0;
  for (const auto& run : series.runs)
    if (run.entry.mu == mu && run.estimate("h")) sum += run.value("h"), ++count;
  return count ? sum / count : 0;
}

Figure flow_rule_figure(const SeriesAnalysis& series) {
  auto curves = by_friction(series, "theta", "U");
  auto velocity = [](double inertial, double h) { return inertial * std::pow(h, 1.5); };  // U/sqrt(gd) = I (h/d)^1.5
  auto tan_deg = [](double deg) { return std::tan(deg * M_PI / 180); };
  for (const auto& fit : series.pouliquen) {
    const double h = mean_thickness(series, fit.angles.mu);
    curves.push_back(sampled("Pouliquen, mu = " + label(fit.angles.mu), fit.angles.theta1_deg.value, fit.angles.theta2_deg.value,
                             [&](double theta) -> std::optional<double> {
                               auto i = pouliquen_inertial_number(tan_deg(theta), fit);
                               if (!i) return std::nullopt;
                               return velocity(*i, h);
                             }));
  }
  if (series.mu_of_i)
    for (const auto& angles : series.mu_of_i->angles) {
      const double h = mean_thickness(series, angles.mu), i0 = series.mu_of_i->i0.value;
      curves.push_back(sampled("mu(I), mu = " + label(angles.mu), angles.theta1_deg.value, angles.theta2_deg.value,
                               [&](double theta) -> std::optional<double> {
                                 auto i = mu_of_i_inertial_number(tan_deg(theta), angles, i0);
                                 if (!i) return std::nullopt;
                                 return velocity(*i, h);
                               }));
    }
  auto p = panel("U against tilt with the flow rules (curves at the mean h of each mu)", "theta (deg)", "U / sqrt(g d)", curves);
  const auto measured = by_friction(series, "theta", "U");
  auto [t0, t1] = x_extent(measured);
  double u_max = 0;
  for (const auto& c : measured) u_max = std::max(u_max, *std::max_element(c.y.begin(), c.y.end()));
  p.x_range = std::make_pair(t0 - 1, t1 + 1);
  p.y_range = std::make_pair(0.0, 1.3 * u_max);  // the rules diverge at theta2
  return {"U_vs_theta", "U against theta with Pouliquen's and the mu(I) rule", {p}};
}

std::optional<Figure> length_figure(const SeriesAnalysis& series) {
  std::vector<std::pair<std::string, std::string>> quantities = {{"f", "f (Hz)"}, {"A", "A / sqrt(g d)"}, {"A_mean", "A_mean / sqrt(g d)"}};
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

std::vector<Figure> series_figures(const SeriesAnalysis& series) {
  std::vector<Figure> figures{
      power_law_figure(series, "f_vs_scale", "f_scale", "(sqrt(g d)/U g/d)^(1/2) (Hz)", series.f_vs_scale),
      power_law_figure(series, "f_vs_shear_rate", "shear_rate", "U/h (1/s)", series.f_vs_shear_rate),
      {"A_vs_U", "Peak amplitude A against U", {panel("A against U", "U / sqrt(g d)", "A / sqrt(g d)", by_friction(series, "U", "A"))}},
      {"A_vs_phi", "Peak amplitude A against phi", {panel("A against phi", "phi", "A / sqrt(g d)", by_friction(series, "phi", "A"))}},
      phi_figure(series),
      flow_rule_figure(series)};
  if (auto lengths = length_figure(series)) figures.push_back(*lengths);
  return figures;
}

void write_runs_table(const SeriesAnalysis& series, const std::string& path) {
  const std::vector<std::string> names = {"U", "phi", "h", "I", "shear_rate", "f_scale", "f", "A", "A_mean", "creep_lambda"};
  auto out = open_output(path);
  out << "run,mu,theta_deg,L_d";
  for (const auto& n : names) out << ',' << n << ',' << n << "_error";
  out << '\n';
  for (const auto& run : series.runs) {
    out << run.entry.directory << ',' << run.entry.mu << ',' << run.entry.theta_deg << ',';
    if (run.entry.length_d) out << *run.entry.length_d;
    for (const auto& n : names) {
      auto e = run.estimate(n);
      out << ',' << (e ? std::to_string(e->value) : "") << ',' << (e && e->error ? std::to_string(*e->error) : "");
    }
    out << '\n';
  }
}

}  // namespace

void write_series_outputs(SeriesAnalysis& series, const std::string& out_dir) {
  const std::string figures_dir = out_dir + "/figures";
  std::filesystem::create_directories(figures_dir);
  MarkdownReport report("Series " + series.settings.manifest);
  report.paragraph(std::to_string(series.runs.size()) +
                   " runs, each analysed as by `cdpost run` (see its report for the method). Fits by GSL least squares; "
                   "errors are one sigma from the covariance scaled by the residual variance. Pouliquen's rule with beta = " +
                   label(series.settings.beta) + ". Per-run numbers: runs.csv.");
  report.heading("Fitted numbers");
  report.table(series.fits);
  report.heading("Figures");
  for (const auto& figure : series_figures(series)) {
    if (auto problem = render_figure(figure, figures_dir))
      series.warnings.push_back(*problem);
    else
      report.figure("figures", figure.name, figure.caption);
  }
  report.warnings(series.warnings);
  write_runs_table(series, out_dir + "/runs.csv");
  series.fits.write_csv(out_dir + "/fits.csv");
  series.fits.write_json(out_dir + "/fits.json", series.warnings);
  report.write(out_dir + "/report.md");
}

}  // namespace cdpost
