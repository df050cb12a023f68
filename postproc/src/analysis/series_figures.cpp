// Figures, tables and the Markdown report of a series.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "analysis/along_cell_series.h"
#include "analysis/series_analysis.h"
#include "output/gnuplot.h"
#include "output/report.h"

namespace cdpost {

namespace {

std::string label(double value)
{
  return format_estimate(value, std::nullopt);
}

}  // namespace

std::vector<Curve> by_friction(const SeriesAnalysis& series, const std::string& x, const std::string& y)
{
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

Curve sampled(const std::string& title, double x0, double x1, const std::function<std::optional<double>(double)>& y)
{
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

std::pair<double, double> x_extent(const std::vector<Curve>& curves)
{
  double low = INFINITY, high = -INFINITY;
  for (const auto& c : curves)
    for (double x : c.x) low = std::min(low, x), high = std::max(high, x);
  return {low, high};
}

Figure power_law_figure(const SeriesAnalysis& series, const std::string& name, const std::string& x,
                        const std::string& x_label, const std::optional<PowerLaw>& law)
{
  auto curves = by_friction(series, x, "f");
  if (law && !curves.empty()) {
    auto [x0, x1] = x_extent(curves);
    curves.push_back(sampled("f = " + format_estimate(law->prefactor.value, law->prefactor.error) + " x^(" +
                                 format_estimate(law->exponent.value, law->exponent.error) + ")",
                             x0, x1,
                             [&](double xv) { return law->prefactor.value * std::pow(xv, law->exponent.value); }));
  }
  return {
      name, "Oscillation frequency f against " + x_label, {panel("f against " + x_label, x_label, "f (Hz)", curves)}};
}

Figure phi_figure(const SeriesAnalysis& series)
{
  auto curves = by_friction(series, "U", "phi");
  if (series.phi_of_u && !curves.empty()) {
    auto [u0, u1] = x_extent(curves);
    for (const auto& [mu, phi_c] : series.phi_of_u->phi_c) {
      const double k = series.phi_of_u->k.value, c = phi_c.value;
      curves.push_back(sampled("phi_c - k U, mu = " + label(mu), u0, u1, [=](double u) { return c - k * u; }));
    }
  }
  return {"phi_vs_U",
          "phi against U with the linear law",
          {panel("Area fraction against velocity", "U / sqrt(g d)", "phi", curves)}};
}

// Mean h (in d) of the runs of one friction coefficient: the flow-rule curves are drawn for it.
double mean_thickness(const SeriesAnalysis& series, double mu)
{
  double sum = 0;
  int count = 0;
  for (const auto& run : series.runs)
    if (run.entry.mu == mu && run.estimate("h")) sum += run.value("h"), ++count;
  return count ? sum / count : 0;
}

Figure flow_rule_figure(const SeriesAnalysis& series)
{
  auto curves = by_friction(series, "theta", "U");
  auto velocity = [](double inertial, double h) { return inertial * std::pow(h, 1.5); };  // U/sqrt(gd) = I (h/d)^1.5
  auto tan_deg = [](double deg) { return std::tan(deg * M_PI / 180); };
  for (const auto& fit : series.pouliquen) {
    const double h = mean_thickness(series, fit.angles.mu);
    curves.push_back(sampled("Pouliquen, mu = " + label(fit.angles.mu), fit.angles.theta1_deg.value,
                             fit.angles.theta2_deg.value, [&](double theta) -> std::optional<double> {
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
  auto p = panel("U against tilt with the flow rules (curves at the mean h of each mu)", "theta (deg)", "U / sqrt(g d)",
                 curves);
  const auto measured = by_friction(series, "theta", "U");
  auto [t0, t1] = x_extent(measured);
  double u_max = 0;
  for (const auto& c : measured) u_max = std::max(u_max, *std::max_element(c.y.begin(), c.y.end()));
  p.x_range = std::make_pair(t0 - 1, t1 + 1);
  p.y_range = std::make_pair(0.0, 1.3 * u_max);  // the rules diverge at theta2
  return {"U_vs_theta", "U against theta with Pouliquen's and the mu(I) rule", {p}};
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
    stops.push_back(
        sampled("h_stop(theta), mu = " + label(mu), fit.angles.theta1_deg.value, fit.angles.theta2_deg.value, h_stop));
    froude.push_back(flowing);
    if (!flowing.x.empty())
      froude.push_back(sampled("Fr = beta h/h_stop, beta = " + format_estimate(fit.beta->value, fit.beta->error), 0,
                               *std::max_element(flowing.x.begin(), flowing.x.end()),
                               [&](double x) { return fit.beta->value * x; }));
  }
  if (stops.empty()) return std::nullopt;
  double h_max = 0;
  for (const auto& entry : series.stopped) h_max = std::max(h_max, *entry.h_stop_d);
  auto left = panel("Deposit thickness of the stopped runs", "theta (deg)", "h_stop / d", stops);
  left.y_range = std::make_pair(0.0, 2 * h_max);  // h_stop(theta) diverges at theta1
  left.width = 0.5;
  auto right = panel("Froude number of the flowing runs", "h / h_stop(theta)", "Fr = U / sqrt(g h)", froude);
  right.width = 0.5;
  right.origin_x = 0.5;
  return Figure{"pouliquen_beta_free",
                "Pouliquen's rule with beta free: h_stop(theta) and Fr = beta h/h_stop",
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
      phi_figure(series),
      flow_rule_figure(series)};
  if (auto lengths = length_figure(series)) figures.push_back(*lengths);
  if (auto depth = depth_figure(series)) figures.push_back(*depth);
  if (auto beta = beta_free_figure(series)) figures.push_back(*beta);
  return figures;
}

void write_runs_table(const SeriesAnalysis& series, const std::string& path)
{
  const std::vector<std::string> names = {"U",       "phi", "h", "I",      "shear_rate",
                                          "f_scale", "f",   "A", "A_mean", "creep_lambda"};
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
  for (const auto& fit : fits) header.push_back(fit + (fit == "phi_U" ? " (phi)" : " (tan theta)"));
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

}  // namespace

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
  report.heading("Fitted numbers");
  report.table(series.fits);
  report.heading("Residuals of the flow-rule fits");
  report.paragraph(
      "Observed minus fitted, in tan theta for the flow rules and in phi for phi(U); the rms of each fit is in the "
      "table "
      "above (`*_rms_residual*`); every residual is in residuals.csv.");
  residual_table(report, series);
  report.heading("Decay of the oscillation with depth");
  report.paragraph(
      "The amplitude of v at each run's f per layer (layer_amplitudes.csv, figure amplitude_vs_depth), fitted as "
      "a = a_s exp(z/lambda) over the layers lying wholly in the flowing layer 0 <= z <= h (the bed is left out); "
      "given "
      "only when at least 3 layers qualify and 1/lambda exceeds twice its error (depth_decay.csv). A layer at the "
      "noise "
      "floor flattens the profile; the rms of ln a shows how far the profile is from one exponential.");
  depth_table(report, series);
  along_cell_section(series, report, out_dir);
  report.heading("Figures");
  for (const auto& figure : series_figures(series)) {
    if (auto problem = render_figure(figure, figures_dir)) series.warnings.push_back(*problem);
    else report.figure("figures", figure.name, figure.caption);
  }
  report.warnings(series.warnings);
  write_runs_table(series, out_dir + "/runs.csv");
  write_residuals(series, out_dir + "/residuals.csv");
  write_layer_amplitudes(series, out_dir + "/layer_amplitudes.csv");
  write_depth_decay(series, out_dir + "/depth_decay.csv");
  series.fits.write_csv(out_dir + "/fits.csv");
  series.fits.write_json(out_dir + "/fits.json", series.warnings);
  report.write(out_dir + "/report.md");
}

}  // namespace cdpost
