#include "analysis/series_analysis.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "analysis/published_run.h"
#include "fit/inertial_number.h"
#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/progress.h"
#include "io/tokens.h"

namespace cdpost {

namespace {

std::string trim(const std::string& text)
{
  auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string> split_commas(const std::string& line)
{
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string label(double value)
{
  return format_estimate(value, std::nullopt);
}

std::string mu_label(double mu)
{
  return label(mu);
}

}  // namespace

namespace {

// Column positions of a manifest header; -1 for an absent optional column.
struct ManifestColumns {
  std::vector<std::string> header;
  int run = -1, mu = -1, theta = -1, length = -1, stopped = -1, h_stop = -1;

  explicit ManifestColumns(std::vector<std::string> names) : header(std::move(names))
  {
    run = index_of("run"), mu = index_of("mu"), theta = index_of("theta"), length = index_of("L");
    stopped = index_of("stopped"), h_stop = index_of("h_stop");
  }
  int index_of(const std::string& name) const
  {
    auto found = std::find(header.begin(), header.end(), name);
    return found == header.end() ? -1 : static_cast<int>(found - header.begin());
  }
};

// stopped is 0 or 1 (empty: 0); h_stop is given exactly for the stopped runs.
void read_stop_fields(const std::vector<std::string>& fields, const ManifestColumns& columns, const LineSource& source,
                      ManifestEntry& entry)
{
  if (columns.stopped >= 0 && !fields[static_cast<size_t>(columns.stopped)].empty()) {
    const double flag = parse_number(fields[static_cast<size_t>(columns.stopped)], source, "stopped");
    if (flag != 0 && flag != 1)
      source.fail("stopped must be 0 or 1, found " + fields[static_cast<size_t>(columns.stopped)]);
    entry.stopped = flag == 1;
  }
  const bool has_h_stop = columns.h_stop >= 0 && !fields[static_cast<size_t>(columns.h_stop)].empty();
  if (has_h_stop && !entry.stopped) source.fail("h_stop is given for a run that did not stop (stopped is not 1)");
  if (entry.stopped && !has_h_stop) source.fail("a stopped run needs its deposit thickness in the column h_stop (d)");
  if (!has_h_stop) return;
  entry.h_stop_d = parse_number(fields[static_cast<size_t>(columns.h_stop)], source, "h_stop");
  if (!(*entry.h_stop_d > 0)) source.fail("h_stop must be positive");
}

}  // namespace

std::vector<ManifestEntry> read_manifest(const std::string& path)
{
  LineSource source(path);
  const auto base = std::filesystem::path(path).parent_path();
  std::optional<ManifestColumns> columns;
  std::vector<ManifestEntry> entries;
  std::string line;
  while (source.next(line)) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    auto fields = split_commas(line);
    if (!columns) {
      columns.emplace(fields);
      if (columns->run < 0 || columns->mu < 0 || columns->theta < 0)
        source.fail("the header must name the columns run, mu, theta (and optionally L, stopped, h_stop)");
      continue;
    }
    if (fields.size() != columns->header.size())
      source.fail("expected " + std::to_string(columns->header.size()) + " fields (" + join_names(columns->header) +
                  "), found " + std::to_string(fields.size()));
    ManifestEntry entry;
    entry.name = fields[static_cast<size_t>(columns->run)];
    entry.directory = (base / entry.name).string();
    entry.mu = parse_number(fields[static_cast<size_t>(columns->mu)], source, "mu");
    entry.theta_deg = parse_number(fields[static_cast<size_t>(columns->theta)], source, "theta");
    if (columns->length >= 0) entry.length_d = parse_number(fields[static_cast<size_t>(columns->length)], source, "L");
    read_stop_fields(fields, *columns, source, entry);
    entry.line = source.line_number();
    entries.push_back(entry);
  }
  if (source.line_number() == 0) throw InputError(path, 0, "file is empty");
  if (entries.empty()) source.fail("no runs listed");
  return entries;
}

std::optional<Estimate> SeriesRun::estimate(const std::string& name) const
{
  const auto* row = analysis.results.find(name);
  if (!row) return std::nullopt;
  return Estimate{row->value, row->error};
}

double SeriesRun::value(const std::string& name) const
{
  auto found = estimate(name);
  if (!found) throw AnalysisError("run " + entry.directory + " has no result '" + name + "'");
  return found->value;
}

namespace {

struct SeriesFitter {
  SeriesAnalysis& series;

  // The runs that have I (and phi, where they do) under `definition`.
  std::vector<FlowPoint> flow_points(const LayerDefinition& definition) const
  {
    std::vector<FlowPoint> points;
    for (const auto& run : series.runs) {
      if (!run.estimate(definition.inertial)) continue;
      FlowPoint p;
      p.run = run.entry.name;
      p.mu = run.entry.mu;
      p.theta_deg = run.entry.theta_deg;
      p.inertial_number = run.value(definition.inertial);
      p.velocity = run.value("U");
      if (auto phi = run.estimate(definition.phi)) p.phi = phi->value;
      points.push_back(p);
    }
    return points;
  }

  std::vector<StopPoint> stop_points(double mu) const
  {
    std::vector<StopPoint> points;
    for (const auto& entry : series.stopped)
      if (entry.mu == mu) points.push_back({entry.name, entry.mu, entry.theta_deg, *entry.h_stop_d});
    return points;
  }

  // Runs `fit`, recording a warning instead of failing the series when it cannot be done.
  template <class Fit>
  void attempt(const std::string& what, Fit fit)
  {
    try {
      fit();
    } catch (const AnalysisError& e) {
      series.warnings.push_back(what + " not fitted: " + e.what());
    }
  }

  const ManifestEntry& entry_of(const std::string& name) const
  {
    for (const auto& run : series.runs)
      if (run.entry.name == name) return run.entry;
    // Every residual names a run of the manifest, flowing or stopped.
    return *std::find_if(series.stopped.begin(), series.stopped.end(),
                         [&](const ManifestEntry& e) { return e.name == name; });
  }

  // The rms residual as a fit result, and every residual in series.residuals.
  void record_residuals(const std::string& fit_name, const std::string& suffix, const std::string& quantity,
                        const FitResult& raw, const std::vector<PointResidual>& residuals)
  {
    series.fits.add(fit_name + "_rms_residual" + suffix, raw.rms_residual(), "",
                    "rms of the " + std::to_string(raw.points) + " residuals in " + quantity + " of the fit (" +
                        std::to_string(raw.dof) + " degrees of freedom); per run in residuals.csv");
    for (const auto& r : residuals) {
      const auto& entry = entry_of(r.run);
      series.residuals.push_back({r.run, entry.mu, entry.theta_deg, fit_name, quantity, r.value});
    }
  }

  void pouliquen_fixed(const std::vector<FlowPoint>& points, double mu, DefinitionFits& fits)
  {
    const std::string suffix = "_mu" + mu_label(mu), name = fits.definition.prefix + "pouliquen";
    attempt(scope(fits) + "Pouliquen's rule for mu = " + mu_label(mu), [&] {
      auto fit = fit_pouliquen(points, series.settings.beta);
      auto& r = series.fits;
      r.add(name + "_theta1" + suffix, fit.angles.theta1_deg, "deg",
            "theta1 of Pouliquen's rule (beta = " + format_estimate(fit.beta, std::nullopt) + ")" + of(fits));
      r.add(name + "_theta2" + suffix, fit.angles.theta2_deg, "deg", "theta2 of Pouliquen's rule" + of(fits));
      r.add(name + "_ell" + suffix, fit.ell, "", "l of Pouliquen's rule" + of(fits));
      if (auto c = parameter_correlation(fit.raw, "tan_theta2", "ell"))
        r.add(name + "_corr_theta2_ell" + suffix, *c, "",
              "correlation coefficient of theta2 and l in Pouliquen's rule (fit covariance)" + of(fits));
      record_residuals(name, suffix, "tan_theta", fit.raw, fit.residuals);
      for (double ell : series.settings.held_ell)
        attempt(scope(fits) + "Pouliquen's rule with l held at " + label(ell) + " for mu = " + mu_label(mu), [&] {
          auto held = fit_pouliquen_held_ell(points, series.settings.beta, ell);
          series.held_fits.push_back(
              {fits.definition.prefix, "pouliquen", ell, held.angles, held.raw.rms_residual(), held.raw.dof});
        });
      fits.pouliquen.push_back(fit);
    });
  }

  void pouliquen_free(const std::vector<FlowPoint>& points, double mu)
  {
    const std::string suffix = "_mu" + mu_label(mu), what = " of Pouliquen's rule with beta free";
    attempt("Pouliquen's rule with beta free for mu = " + mu_label(mu), [&] {
      auto fit = fit_pouliquen_free(points, stop_points(mu));
      auto& r = series.fits;
      r.add("pouliquen_betafree_ell_over_beta" + suffix, fit.ell_over_beta, "",
            "l/beta" + what + " (the only combination the flowing runs determine)");
      if (fit.beta) {
        r.add("pouliquen_betafree_theta1" + suffix, fit.angles.theta1_deg, "deg",
              "theta1" + what + ", flowing and stopped runs");
        r.add("pouliquen_betafree_theta2" + suffix, fit.angles.theta2_deg, "deg", "theta2" + what);
        r.add("pouliquen_betafree_ell" + suffix, *fit.ell, "", "l" + what + ", fixed by h_stop of the stopped runs");
        r.add("pouliquen_betafree_beta" + suffix, *fit.beta, "", "beta" + what);
        r.add("pouliquen_betafree_stopped_runs" + suffix, fit.stopped_runs, "",
              "stopped runs in the fit with beta free");
      } else {
        series.warnings.push_back(
            "Pouliquen's rule with beta free, mu = " + mu_label(mu) +
            ": no stopped run, so beta and l are not determined separately (flowing runs depend on them only "
            "through beta/l; h_stop of a stopped run fixes l): only l/beta is given");
      }
      record_residuals("pouliquen_betafree", suffix, "tan_theta", fit.raw, fit.residuals);
      series.pouliquen_free.push_back(fit);
    });
  }

  // The points of the frictions whose runs span `needed` angles; a warning names the others
  // (a series at one angle, such as the cell-length series, has no flow rule).
  std::vector<FlowPoint> points_at_enough_angles(const std::vector<FlowPoint>& points, size_t needed,
                                                 const std::string& rule)
  {
    std::vector<FlowPoint> kept;
    for (double mu : friction_values(points)) {
      auto of_mu = points_with_mu(points, mu);
      if (angle_count(of_mu) >= needed) kept.insert(kept.end(), of_mu.begin(), of_mu.end());
      else
        series.warnings.push_back(rule + ": the runs at mu = " + mu_label(mu) + " (" +
                                  std::to_string(angle_count(of_mu)) + " angle(s)) are left out: it needs " +
                                  std::to_string(needed) + " angles per friction coefficient");
    }
    return kept;
  }

  // What a description of the packing definition's fits ends with, and what its warnings start
  // with; both "" for the surface definition, whose names carry no prefix either.
  static std::string of(const DefinitionFits& fits)
  {
    return fits.definition.prefix.empty() ? "" : "; " + fits.definition.description;
  }
  static std::string scope(const DefinitionFits& fits)
  {
    return fits.definition.prefix.empty() ? "" : "with h_packing and phi_bulk: ";
  }

  void mu_of_i(const std::vector<FlowPoint>& points, DefinitionFits& fits)
  {
    const std::string name = fits.definition.prefix + "muI";
    attempt(scope(fits) + "the mu(I) rule", [&] {
      const auto kept = points_at_enough_angles(points, kMuOfIAngles, scope(fits) + "the mu(I) rule");
      auto fit = fit_mu_of_i(kept);
      auto& r = series.fits;
      r.add(name + "_I0", fit.i0, "", "I0 of the mu(I) rule, shared by every mu" + of(fits));
      for (size_t m = 0; m < fit.angles.size(); ++m) {
        const auto& a = fit.angles[m];
        r.add(name + "_theta1_mu" + mu_label(a.mu), a.theta1_deg, "deg", "theta1 of the mu(I) rule" + of(fits));
        r.add(name + "_theta2_mu" + mu_label(a.mu), a.theta2_deg, "deg", "theta2 of the mu(I) rule" + of(fits));
        if (auto c = parameter_correlation(fit.raw, "I0", "tan_theta2_" + std::to_string(m)))
          r.add(name + "_corr_I0_theta2_mu" + mu_label(a.mu), *c, "",
                "correlation coefficient of I0 and theta2 in the mu(I) rule (fit covariance)" + of(fits));
      }
      record_residuals(name, "", "tan_theta", fit.raw, fit.residuals);
      for (double i0 : series.settings.held_i0)
        attempt(scope(fits) + "the mu(I) rule with I0 held at " + label(i0), [&] {
          auto held = fit_mu_of_i_held_i0(kept, i0);
          for (const auto& a : held.angles)
            series.held_fits.push_back({fits.definition.prefix, "muI", i0, a, held.raw.rms_residual(), held.raw.dof});
        });
      fits.mu_of_i = fit;
    });
  }

  void phi_laws(const std::vector<FlowPoint>& points, DefinitionFits& fits)
  {
    const std::string& prefix = fits.definition.prefix;
    attempt(scope(fits) + "phi = phi_c(mu) - k U/sqrt(g d)", [&] {
      auto fit = fit_phi_velocity(points);
      series.fits.add(prefix + "phi_k", fit.k, "",
                      "k of phi = phi_c(mu) - k U/sqrt(g d), shared by every mu" + of(fits));
      for (const auto& [mu, phi_c] : fit.phi_c)
        series.fits.add(prefix + "phi_c_mu" + mu_label(mu), phi_c, "", "phi_c of the linear phi(U) law" + of(fits));
      record_residuals(prefix + "phi_U", "", "phi", fit.raw, fit.residuals);
      fits.phi_of_u = fit;
    });
    const auto mus = friction_values(points);
    for (double mu : mus.size() > 1 ? mus : std::vector<double>{})  // one friction: the common fit is its own
      attempt(scope(fits) + "phi = phi_c - k U/sqrt(g d) at mu = " + mu_label(mu) + " alone", [&] {
        const auto of_mu = points_with_mu(points, mu);
        const auto fit = fit_phi_velocity(of_mu);
        const std::string suffix = "_mu" + mu_label(mu),
                          what =
                              " of phi = phi_c - k U/sqrt(g d) fitted to mu = " + mu_label(mu) + " alone (its own k)";
        series.fits.add(prefix + "phi_c_own_k" + suffix, fit.phi_c.front().second, "", "phi_c" + what + of(fits));
        series.fits.add(prefix + "phi_k_own" + suffix, fit.k, "", "k" + what + of(fits));
        double slowest = INFINITY;
        for (const auto& p : of_mu) slowest = std::min(slowest, p.velocity);
        series.fits.add(prefix + "phi_slowest_U" + suffix, slowest, "sqrt(g d)",
                        "smallest U of the runs at mu = " + mu_label(mu) + ": phi_c extrapolates from it to U = 0");
      });
    attempt(scope(fits) + "phi = phi_c(mu) - k_I I", [&] {
      auto fit = fit_phi_inertial(points);
      series.fits.add(prefix + "phiI_k", fit.k, "", "k_I of phi = phi_c(mu) - k_I I, shared by every mu" + of(fits));
      for (const auto& [mu, phi_c] : fit.phi_c)
        series.fits.add(prefix + "phiI_c_mu" + mu_label(mu), phi_c, "", "phi_c of the linear phi(I) law" + of(fits));
      record_residuals(prefix + "phi_I", "", "phi", fit.raw, fit.residuals);
      fits.phi_of_i = fit;
    });
  }

  void flow_rules()
  {
    for (const auto& definition : {kSurfaceDefinition, kPackingDefinition}) {
      const auto points = flow_points(definition);
      if (points.empty()) {
        series.warnings.push_back("no run has " + definition.inertial + ": no fit with " + definition.description);
        continue;
      }
      if (points.size() < series.runs.size())
        series.warnings.push_back(std::to_string(series.runs.size() - points.size()) + " runs without " +
                                  definition.inertial + " left out of the fits with " + definition.description);
      DefinitionFits fits{definition, {}, std::nullopt, std::nullopt, std::nullopt};
      const auto mus = friction_values(points);
      for (double mu : mus) {
        pouliquen_fixed(points_with_mu(points, mu), mu, fits);
        if (definition.prefix.empty()) pouliquen_free(points_with_mu(points, mu), mu);
      }
      if (definition.prefix.empty())
        for (const auto& entry : series.stopped)
          if (std::find(mus.begin(), mus.end(), entry.mu) == mus.end())
            series.warnings.push_back("stopped run " + entry.directory + " (mu = " + mu_label(entry.mu) +
                                      ") not used: no flowing run at that mu");
      mu_of_i(points, fits);
      phi_laws(points, fits);
      series.definitions.push_back(fits);
    }
  }

  // A result of a run by name; "L" is the manifest's cell length.
  static std::optional<double> quantity(const SeriesRun& run, const std::string& name)
  {
    if (name == "L") return run.entry.length_d;
    auto e = run.estimate(name);
    return e ? std::optional<double>(e->value) : std::nullopt;
  }

  // The runs (of friction `mu`, if given) having both quantities, as two columns.
  std::pair<std::vector<double>, std::vector<double>> columns(const std::string& x, const std::string& y,
                                                              std::optional<double> mu = std::nullopt) const
  {
    std::pair<std::vector<double>, std::vector<double>> xy;
    for (const auto& run : series.runs) {
      auto xv = quantity(run, x), yv = quantity(run, y);
      if (xv && yv && (!mu || run.entry.mu == *mu)) {
        xy.first.push_back(*xv);
        xy.second.push_back(*yv);
      }
    }
    return xy;
  }

  // Each analysis over all runs (suffix and scope "") and, when the series has several
  // frictions, per mu (suffix "_mu<mu>", scope " (mu = <mu>)").
  template <class Analysis>
  void overall_and_per_friction(Analysis analysis)
  {
    analysis(std::optional<double>(), std::string(), std::string());
    std::set<double> mus;
    for (const auto& run : series.runs) mus.insert(run.entry.mu);
    if (mus.size() > 1)
      for (double mu : mus) analysis(std::optional<double>(mu), "_mu" + mu_label(mu), " (mu = " + mu_label(mu) + ")");
  }

  // Rows r_name, stem_n and stem_p_value (each + suffix): r, n and the p-value of a correlation;
  // with fewer than 3 runs a warning says why they are missing.
  void significance(const std::string& r_name, const std::string& stem, const std::string& suffix,
                    const std::string& scope, const std::string& what, const std::vector<double>& x,
                    const std::vector<double>& y)
  {
    if (x.size() < 3) {
      series.warnings.push_back("correlation of " + what + scope + ": " + std::to_string(x.size()) +
                                " runs, no correlation or p-value (they need 3)");
      return;
    }
    attempt("correlation of " + what + scope, [&] {
      auto test = test_correlation(x, y);
      series.fits.add(r_name + suffix, test.r, "", "Pearson correlation r of " + what + scope);
      series.fits.add(stem + "_n" + suffix, test.n, "", "runs in the correlation of " + what + scope);
      series.fits.add(stem + "_p_value" + suffix, test.p_value, "",
                      "two-sided p-value of r under no correlation (Student t, n - 2 degrees of freedom)");
    });
  }

  // The law is a line in log-log, so its significance is that of the correlation of ln f with
  // ln x (the t-test of the exponent); the correlation on linear scales is kept beside it.
  void power_law(const std::string& x, const std::string& name, const std::string& meaning,
                 std::optional<PowerLaw>& slot)
  {
    overall_and_per_friction([&](std::optional<double> mu, const std::string& suffix, const std::string& scope) {
      auto [xs, fs] = columns(x, "f", mu);
      attempt(meaning + scope, [&] {
        auto law = fit_power_law(xs, fs);
        series.fits.add(name + "_exponent" + suffix, law.exponent, "", "exponent n of " + meaning + scope);
        series.fits.add(name + "_prefactor" + suffix, law.prefactor, "", "prefactor c of " + meaning + scope);
        if (law.correlation)
          series.fits.add(name + "_correlation" + suffix, *law.correlation, "",
                          "Pearson correlation of f with " + x + " on linear scales" + scope);
        if (!mu) slot = law;
        auto logarithms = [](std::vector<double> v) {
          for (double& e : v) e = std::log(e);
          return v;
        };
        significance(name + "_log_correlation", name, suffix, scope, "ln f with ln " + x, logarithms(xs),
                     logarithms(fs));
      });
    });
  }

  void correlation_of(const std::string& x, const std::string& y, const std::string& label)
  {
    overall_and_per_friction([&](std::optional<double> mu, const std::string& suffix, const std::string& scope) {
      auto [xs, ys] = columns(x, y, mu);
      if (!xs.empty())
        significance("correlation_" + label, "correlation_" + label, suffix, scope, y + " with " + x, xs, ys);
    });
  }

  void scalings()
  {
    power_law("f_scale", "f_vs_scale", "f against (sqrt(g d)/U g/d)^(1/2): f = c x^n", series.f_vs_scale);
    power_law("shear_rate", "f_vs_shear_rate", "f against U/h: f = c (U/h)^n", series.f_vs_shear_rate);
    correlation_of("U", "A", "A_U");
    correlation_of("phi", "A", "A_phi");
  }

  // Over the runs with an L column only (the L series is at one friction): the correlation of
  // f, A and A_mean with L and, over 3 or more lengths, their power law y = c L^n.
  void length_dependence()
  {
    for (const std::string y : {"f", "A", "A_mean"}) {
      auto [lengths, ys] = columns("L", y);
      if (lengths.empty()) continue;
      significance("correlation_" + y + "_L", "correlation_" + y + "_L", "", "", y + " with L", lengths, ys);
      if (std::set<double>(lengths.begin(), lengths.end()).size() < 3) continue;
      attempt(y + " against L", [&] {
        auto law = fit_power_law(lengths, ys);
        const std::string meaning = y + " against L: " + y + " = c (L/d)^n";
        series.fits.add(y + "_vs_L_exponent", law.exponent, "", "exponent n of " + meaning);
        series.fits.add(y + "_vs_L_prefactor", law.prefactor, "", "prefactor c of " + meaning);
      });
    }
  }
};

// The decay length of the amplitude at f with depth, for each run with layers and h.
void depth_decay(SeriesAnalysis& series)
{
  for (auto& run : series.runs) {
    const auto& layers = run.analysis.layers;
    if (layers.empty() || !run.estimate("h")) continue;
    std::vector<double> z, amplitude;
    for (const auto& layer : layers) z.push_back(layer.z_d), amplitude.push_back(layer.amplitude_at_f);
    try {
      run.depth_decay = fit_depth_decay(z, amplitude, run.value("h"));
    } catch (const AnalysisError& e) {
      series.warnings.push_back(run.entry.directory + ": no decay length of the amplitude with depth: " + e.what());
    }
  }
}

// The run's inertial number read as GDR MiDi's (fit/inertial_number.h): I_bagnold from U, h and
// phi, I_local at mid-layer from its profiles u(z) and phi(z), each added to its results.
void add_inertial_numbers(SeriesRun& run, std::vector<std::string>& warnings)
{
  const auto velocity = run.estimate("U"), thickness = run.estimate("h"), phi = run.estimate("phi");
  if (!velocity || !thickness || !phi) return;
  const double theta = run.entry.theta_deg;
  const double bagnold = bagnold_inertial_number(velocity->value, thickness->value, phi->value, theta);
  auto& results = run.analysis.results;
  std::optional<double> bagnold_error;
  if (velocity->error) bagnold_error = bagnold * *velocity->error / velocity->value;
  results.add("I_bagnold", Estimate{bagnold, bagnold_error}, "",
              "GDR MiDi's inertial number with the Bagnold shear rate 5U/(2h) and the basal pressure phi rho g h cos "
              "theta: 2.5 U/(h^1.5 sqrt(phi cos theta)); error from U alone");
  const auto& profile = run.analysis.profile;
  if (!profile || profile->phi.empty()) {
    warnings.push_back(run.entry.directory + ": no u(z) and phi(z), no local inertial number");
    return;
  }
  try {
    const auto local =
        local_inertial_number(profile->z_d, profile->u_reduced, profile->phi, kLocalHeightFraction * thickness->value,
                              kLocalBandFraction * thickness->value, theta);
    const std::string where = " at mid-layer, z = h/2 (shear rate fitted over h/2 +- h/10)";
    results.add("I_local", local.inertial, "",
                "GDR MiDi's inertial number gamma_dot d/sqrt(P/rho)" + where +
                    "; P the weight of the grains above; error from the shear rate's");
    results.add("shear_rate_local", local.shear_rate, "sqrt(g/d)", "du/dz" + where);
    results.add("pressure_local", local.pressure, "rho g d",
                "weight of the grains above z = h/2: cos theta x integral of phi");
    results.add("phi_local", local.phi, "", "mean phi of the bins" + where);
  } catch (const AnalysisError& e) {
    warnings.push_back(run.entry.directory + ": no local inertial number: " + e.what());
  }
}

// The creep length a guide line on the source's semi-log inset follows (fit/creep.h), from the
// run's u(z), added to its results.
void add_first_decade_decay(SeriesRun& run, std::vector<std::string>& warnings)
{
  const auto& profile = run.analysis.profile;
  if (!profile) return;
  if (auto decay = first_decade_decay(profile->z_d, profile->u_reduced))
    run.analysis.results.add("creep_lambda_first_decade", decay->lambda, "d",
                             "decay length of u0 exp(z/lambda) over the first decade of u below the wall tops (" +
                                 std::to_string(decay->points) + " bins, to " +
                                 format_estimate(decay->depth_bottom_d, std::nullopt) + " d below)");
  else
    warnings.push_back(run.entry.directory +
                       ": u does not decay over a first decade of 3 bins or more below the "
                       "wall tops: no creep_lambda_first_decade");
}

}  // namespace

SeriesAnalysis analyse_series(const SeriesSettings& settings)
{
  SeriesAnalysis series;
  series.settings = settings;
  const auto entries = read_manifest(settings.manifest);
  if (!settings.source_file.empty()) series.source = read_source(settings.source_file);
  Progress progress("analysing runs", true, settings.run.progress);
  for (size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].stopped) {
      series.stopped.push_back(entries[i]);
      continue;
    }
    progress.update(static_cast<double>(i) / entries.size(), entries[i].directory);
    RunSettings run_settings = settings.run;
    run_settings.directory = entries[i].directory;
    if (entries[i].length_d) run_settings.cell_length_d = entries[i].length_d;
    try {
      const bool published = is_published_run(run_settings.directory);
      if (!published && settings.complete_run) settings.complete_run(run_settings);
      series.runs.push_back({entries[i],
                             published ? read_published_run(run_settings.directory) : analyse_run(run_settings),
                             std::nullopt, recorded_deck_variable(run_settings.directory, "reading") == "layer"});
    } catch (const std::exception& e) {
      throw InputError(settings.manifest, entries[i].line, std::string("run failed: ") + e.what());
    }
    for (const auto& w : series.runs.back().analysis.warnings)
      series.warnings.push_back(entries[i].directory + ": " + w);
  }
  if (series.runs.empty())
    throw InputError(settings.manifest, 0, "every run listed has stopped: nothing flows to analyse");
  for (auto& run : series.runs) {
    add_inertial_numbers(run, series.warnings);
    add_first_decade_decay(run, series.warnings);
  }
  SeriesFitter fitter{series};
  fitter.flow_rules();
  fitter.scalings();
  fitter.length_dependence();
  depth_decay(series);
  return series;
}

}  // namespace cdpost
