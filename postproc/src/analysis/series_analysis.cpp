#include "analysis/series_analysis.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/progress.h"
#include "io/tokens.h"

namespace cdpost {

namespace {

std::string trim(const std::string& text) {
  auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string mu_label(double mu) { return format_estimate(mu, std::nullopt); }

}  // namespace

std::vector<ManifestEntry> read_manifest(const std::string& path) {
  LineSource source(path);
  const auto base = std::filesystem::path(path).parent_path();
  std::vector<std::string> header;
  std::vector<ManifestEntry> entries;
  std::string line;
  auto index_of = [&](const std::string& name) {
    auto found = std::find(header.begin(), header.end(), name);
    return found == header.end() ? -1 : static_cast<int>(found - header.begin());
  };
  int run = -1, mu = -1, theta = -1, length = -1;
  while (source.next(line)) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    auto fields = split_commas(line);
    if (header.empty()) {
      header = fields;
      run = index_of("run"), mu = index_of("mu"), theta = index_of("theta"), length = index_of("L");
      if (run < 0 || mu < 0 || theta < 0) source.fail("the header must name the columns run, mu, theta (and optionally L)");
      continue;
    }
    if (fields.size() != header.size())
      source.fail("expected " + std::to_string(header.size()) + " fields (" + join_names(header) + "), found " + std::to_string(fields.size()));
    ManifestEntry entry;
    entry.directory = (base / fields[static_cast<size_t>(run)]).string();
    entry.mu = parse_number(fields[static_cast<size_t>(mu)], source, "mu");
    entry.theta_deg = parse_number(fields[static_cast<size_t>(theta)], source, "theta");
    if (length >= 0) entry.length_d = parse_number(fields[static_cast<size_t>(length)], source, "L");
    entry.line = source.line_number();
    entries.push_back(entry);
  }
  if (source.line_number() == 0) throw InputError(path, 0, "file is empty");
  if (entries.empty()) source.fail("no runs listed");
  return entries;
}

std::optional<Estimate> SeriesRun::estimate(const std::string& name) const {
  const auto* row = analysis.results.find(name);
  if (!row) return std::nullopt;
  return Estimate{row->value, row->error};
}

double SeriesRun::value(const std::string& name) const {
  auto found = estimate(name);
  if (!found) throw AnalysisError("run " + entry.directory + " has no result '" + name + "'");
  return found->value;
}

namespace {

struct SeriesFitter {
  SeriesAnalysis& series;

  std::vector<FlowPoint> flow_points() const {
    std::vector<FlowPoint> points;
    for (const auto& run : series.runs) {
      if (!run.estimate("I")) continue;
      FlowPoint p;
      p.mu = run.entry.mu;
      p.theta_deg = run.entry.theta_deg;
      p.inertial_number = run.value("I");
      p.velocity = run.value("U");
      if (auto phi = run.estimate("phi")) p.phi = phi->value;
      points.push_back(p);
    }
    return points;
  }

  // Runs `fit`, recording a warning instead of failing the series when it cannot be done.
  template <class Fit>
  void attempt(const std::string& what, Fit fit) {
    try {
      fit();
    } catch (const AnalysisError& e) {
      series.warnings.push_back(what + " not fitted: " + e.what());
    }
  }

  void flow_rules() {
    const auto points = flow_points();
    auto& r = series.fits;
    for (double mu : friction_values(points))
      attempt("Pouliquen's rule for mu = " + mu_label(mu), [&] {
        auto fit = fit_pouliquen(points_with_mu(points, mu), series.settings.beta);
        const std::string suffix = "_mu" + mu_label(mu);
        r.add("pouliquen_theta1" + suffix, fit.angles.theta1_deg, "deg", "theta1 of Pouliquen's rule (beta = " + format_estimate(fit.beta, std::nullopt) + ")");
        r.add("pouliquen_theta2" + suffix, fit.angles.theta2_deg, "deg", "theta2 of Pouliquen's rule");
        r.add("pouliquen_ell" + suffix, fit.ell, "", "l of Pouliquen's rule");
        series.pouliquen.push_back(fit);
      });
    attempt("the mu(I) rule", [&] {
      auto fit = fit_mu_of_i(points);
      r.add("muI_I0", fit.i0, "", "I0 of the mu(I) rule, shared by every mu");
      for (const auto& a : fit.angles) {
        r.add("muI_theta1_mu" + mu_label(a.mu), a.theta1_deg, "deg", "theta1 of the mu(I) rule");
        r.add("muI_theta2_mu" + mu_label(a.mu), a.theta2_deg, "deg", "theta2 of the mu(I) rule");
      }
      series.mu_of_i = fit;
    });
    attempt("phi = phi_c(mu) - k U/sqrt(g d)", [&] {
      auto fit = fit_phi_velocity(points);
      r.add("phi_k", fit.k, "", "k of phi = phi_c(mu) - k U/sqrt(g d), shared by every mu");
      for (const auto& [mu, phi_c] : fit.phi_c) r.add("phi_c_mu" + mu_label(mu), phi_c, "", "phi_c of the linear phi(U) law");
      series.phi_of_u = fit;
    });
  }

  // The runs having both results, as two columns.
  std::pair<std::vector<double>, std::vector<double>> columns(const std::string& x, const std::string& y) const {
    std::pair<std::vector<double>, std::vector<double>> xy;
    for (const auto& run : series.runs)
      if (run.estimate(x) && run.estimate(y)) {
        xy.first.push_back(run.value(x));
        xy.second.push_back(run.value(y));
      }
    return xy;
  }

  void power_law(const std::string& x, const std::string& name, const std::string& meaning, std::optional<PowerLaw>& slot) {
    attempt(meaning, [&] {
      auto [xs, fs] = columns(x, "f");
      auto law = fit_power_law(xs, fs);
      series.fits.add(name + "_exponent", law.exponent, "", "exponent n of " + meaning);
      series.fits.add(name + "_prefactor", law.prefactor, "", "prefactor c of " + meaning);
      if (law.correlation) series.fits.add(name + "_correlation", *law.correlation, "", "Pearson correlation of " + meaning.substr(0, meaning.find(':')));
      slot = law;
    });
  }

  void correlation_of(const std::string& x, const std::string& y, const std::string& label) {
    auto [xs, ys] = columns(x, y);
    if (xs.size() >= 3) series.fits.add("correlation_" + label, correlation(xs, ys), "", "Pearson correlation of " + y + " with " + x);
  }

  void scalings() {
    power_law("f_scale", "f_vs_scale", "f against (sqrt(g d)/U g/d)^(1/2): f = c x^n", series.f_vs_scale);
    power_law("shear_rate", "f_vs_shear_rate", "f against U/h: f = c (U/h)^n", series.f_vs_shear_rate);
    correlation_of("U", "A", "A_U");
    correlation_of("phi", "A", "A_phi");
  }

  void length_dependence() {
    std::vector<double> lengths, f, a, a_mean;
    for (const auto& run : series.runs)
      if (run.entry.length_d) {
        lengths.push_back(*run.entry.length_d);
        f.push_back(run.value("f"));
        a.push_back(run.value("A"));
        a_mean.push_back(run.value("A_mean"));
      }
    if (lengths.size() < 3) return;
    series.fits.add("correlation_f_L", correlation(lengths, f), "", "Pearson correlation of f with L");
    series.fits.add("correlation_A_L", correlation(lengths, a), "", "Pearson correlation of A with L");
    series.fits.add("correlation_A_mean_L", correlation(lengths, a_mean), "", "Pearson correlation of A_mean with L");
  }
};

}  // namespace

SeriesAnalysis analyse_series(const SeriesSettings& settings) {
  SeriesAnalysis series;
  series.settings = settings;
  const auto entries = read_manifest(settings.manifest);
  Progress progress("analysing runs", true, settings.run.progress);
  for (size_t i = 0; i < entries.size(); ++i) {
    progress.update(static_cast<double>(i) / entries.size(), entries[i].directory);
    RunSettings run_settings = settings.run;
    run_settings.directory = entries[i].directory;
    try {
      series.runs.push_back({entries[i], analyse_run(run_settings)});
    } catch (const std::exception& e) {
      throw InputError(settings.manifest, entries[i].line, std::string("run failed: ") + e.what());
    }
    for (const auto& w : series.runs.back().analysis.warnings) series.warnings.push_back(entries[i].directory + ": " + w);
  }
  SeriesFitter fitter{series};
  fitter.flow_rules();
  fitter.scalings();
  fitter.length_dependence();
  return series;
}

}  // namespace cdpost
