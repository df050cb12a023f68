// The comparison itself: each run analysed as by cdpost run, its spectral peaks in the flow and
// contact bands, and how the soft runs' peaks move with the stiffness.
#include "comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "comparison_reading.h"
#include "comparison_tables.h"
#include "fit/linear_fit.h"
#include "io/line_source.h"
#include "signal/stationary.h"

namespace cdref {

namespace fs = std::filesystem;

std::optional<double> ComparedRun::wall_per_physical_second() const
{
  if (!loop_seconds || !physical_seconds || *physical_seconds <= 0) return std::nullopt;
  return *loop_seconds / *physical_seconds;
}

std::optional<double> ComparedRun::cpu_per_physical_second() const
{
  auto wall = wall_per_physical_second();
  if (!wall) return std::nullopt;
  if (process_cpu_share) return *wall * std::min(1.0, *process_cpu_share);
  if (cpu_percent) return *wall * std::min(1.0, *cpu_percent / 100);
  return std::nullopt;
}

namespace {

std::string make_label(const ComparedRun& run)
{
  if (run.model == "rigid") {
    auto tolerance = run.info.text("tolerance");
    return "rigid" + (tolerance ? " tol " + *tolerance : std::string());
  }
  if (run.model == "unknown") return fs::path(run.directory).filename().string();
  std::string code = run.code == "lammps-granular" ? "granular" : run.code;
  auto overlap = run.info.text("overlap_target");
  return code + " " + run.model + (overlap ? " " + *overlap : std::string());
}

// Chooses the analysis window: the settings' override, else the detected stationary regime,
// else (flagged) the second half of the run.
void choose_window(ComparedRun& run, cdpost::RunSettings& s, const Samples& samples)
{
  if (s.t_start || s.t_end) {
    run.window_note = "given on the command line";
    return;
  }
  try {
    cdpost::detect_stationary(samples.time, samples.u_flow, s.criterion);
    run.window_note = "detected stationary regime";
  } catch (const cdpost::AnalysisError& e) {
    run.stationary = false;
    s.t_start = samples.time[samples.time.size() / 2];
    run.window_note = std::string("NOT STATIONARY (") + e.what() +
                      "): analysed over the second half, t >= " + short_number(*s.t_start);
  }
}

// The highest bin in [lo, hi] if it is a peak: a bin inside the band, not at one of its ends
// (the maximum of a spectrum that only falls through the band sits at its lower end).
std::optional<cdpost::SpectralPeak> band_peak(const cdpost::Spectrum& spectrum, double lo, double hi)
{
  if (!(lo < hi)) return std::nullopt;
  const auto& f = spectrum.frequency_hz;
  const auto& a = spectrum.amplitude;
  size_t first = static_cast<size_t>(std::lower_bound(f.begin(), f.end(), lo) - f.begin());
  size_t end = static_cast<size_t>(std::upper_bound(f.begin(), f.end(), hi) - f.begin());
  if (end < first + 3) return std::nullopt;
  size_t top = static_cast<size_t>(
      std::max_element(a.begin() + static_cast<long>(first), a.begin() + static_cast<long>(end)) - a.begin());
  if (top == first || top == end - 1) return std::nullopt;
  return cdpost::find_peak(spectrum, lo, hi);
}

// The contact band's most prominent feature: the spectrum is smoothed over a relative
// bandwidth (each bin averaged over |f' - f| <= smoothing f, which keeps a resonance as broad
// as a damped contact's, Q ~ 2, and averages out the scatter of a few Welch segments), a power
// law A = c f^b is fitted to the smoothed band (log-log least squares), and the largest ratio
// of smoothed amplitude to that law is returned: a falling broadband spectrum reads about 1.
struct BandExcess {
  double ratio = 0;
  double frequency_hz = 0;
};
std::optional<BandExcess> band_excess(const cdpost::Spectrum& spectrum, double lo, double hi, double smoothing)
{
  const auto& f = spectrum.frequency_hz;
  const auto& a = spectrum.amplitude;
  std::vector<double> x, y;
  for (size_t k = 0; k < f.size(); ++k) {
    if (f[k] < lo || f[k] > hi || f[k] <= 0) continue;
    double sum = 0;
    int n = 0;
    for (size_t j = 0; j < f.size(); ++j)
      if (std::abs(f[j] - f[k]) <= smoothing * f[k]) {
        sum += a[j];
        ++n;
      }
    if (sum <= 0) continue;
    x.push_back(f[k]);
    y.push_back(sum / n);
  }
  if (x.size() < 5) return std::nullopt;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double n = static_cast<double>(x.size());
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  BandExcess best;
  for (size_t i = 0; i < x.size(); ++i) {
    const double ratio = y[i] / std::exp(intercept + slope * std::log(x[i]));
    if (ratio > best.ratio) best = {ratio, x[i]};
  }
  return best;
}

void find_band_peaks(ComparedRun& run, const CompareSettings& settings)
{
  const auto& spectrum = run.analysis.spectrum;
  const double nyquist = spectrum.frequency_hz.back();
  const double fmin = run.analysis.settings.peak_fmin_hz;
  run.flow_peak = band_peak(spectrum, fmin, std::min(settings.flow_band_max_hz, nyquist));
  if (!run.f_contact_hz) return;
  const double lo = settings.contact_band_low * *run.f_contact_hz;
  const double hi = std::min(settings.contact_band_high * *run.f_contact_hz, nyquist);
  auto excess = band_excess(spectrum, lo, hi, settings.smoothing);
  if (!excess) return;
  run.contact_excess = excess->ratio;
  if (excess->ratio < settings.peak_excess) return;
  // The peak itself: the highest bin within the smoothing bandwidth of the feature.
  const double half = std::max(settings.smoothing * excess->frequency_hz, 2.5 * spectrum.resolution_hz);
  run.contact_peak =
      cdpost::find_peak(spectrum, std::max(lo, excess->frequency_hz - half), std::min(hi, excess->frequency_hz + half));
}

ComparedRun analyse_one(const std::string& dir, const CompareSettings& settings, std::vector<std::string>& warnings)
{
  ComparedRun run;
  run.directory = dir;
  if (!fs::is_directory(dir)) throw cdpost::InputError(dir, 0, "not a directory");
  run.info = read_run_info((fs::path(dir) / "run.info").string());
  run.code = run.info.text("code").value_or("unknown");
  run.model = run.info.text("model").value_or("unknown");
  run.label = make_label(run);
  run.k_eff_n_per_m = run.info.number("k_eff");
  run.k_reduced = run.info.number("k_reduced");
  run.f_contact_hz = run.info.number("f_contact");
  run.overlap_target = run.info.number("overlap_target");

  cdpost::RunSettings s = settings.run;
  s.directory = dir;
  if (auto d = run.info.number("d")) s.units.d_m = *d;
  if (auto walls = run.info.number("bed_walls_d")) s.z0 = *walls * s.units.d_m / s.units.length_unit_m;
  // With the deck's dt known, time is TimeStep x dt: exact, where a printed time column may
  // carry too few digits for a regular axis (LIGGGHTS prints 6 and has none).
  if (auto dt = run.info.number("dt")) {
    s.timestep_size = *dt / s.units.time_unit_s;
    s.columns.time = "(TimeStep x dt of run.info)";
  }
  const Samples samples = read_samples(s);
  choose_window(run, s, samples);
  run.analysis = cdpost::analyse_run(s);
  for (const auto& w : run.analysis.warnings) warnings.push_back(run.label + ": " + w);
  find_band_peaks(run, settings);
  read_cost(run, samples, s.units.time_unit_s, warnings);
  read_overlaps(run, settings, s, samples, warnings);
  if (!run.stationary) warnings.push_back(run.label + ": " + run.window_note);
  return run;
}

void make_labels_unique(std::vector<ComparedRun>& runs)
{
  std::map<std::string, int> seen;
  for (const auto& r : runs) ++seen[r.label];
  for (auto& r : runs)
    if (seen[r.label] > 1) r.label += " (" + fs::path(r.directory).filename().string() + ")";
}

// How the soft runs' peaks move with k: f = c k^n per code and model, for the contact-band
// peak and the flow-band peak.
void fit_peak_shifts(Comparison& comparison)
{
  std::map<std::string, std::vector<const ComparedRun*>> groups;
  for (const auto& r : comparison.runs)
    if (r.soft() && r.k_eff_n_per_m) groups[r.code + "_" + r.model].push_back(&r);
  for (const auto& [group, runs] : groups) {
    if (runs.size() < 2) continue;
    auto fit = [&](const char* which, auto peak_of) {
      std::vector<double> k, f;
      for (const auto* r : runs)
        if (auto p = peak_of(*r)) {
          k.push_back(*r->k_eff_n_per_m);
          f.push_back(p->frequency_hz);
        }
      std::set<double> distinct(k.begin(), k.end());
      if (distinct.size() < 2) return;
      try {
        auto law = cdpost::fit_power_law(k, f);
        comparison.fits.add(std::string(which) + "_exponent_" + group, law.exponent, "",
                            std::string("n in f = c k^n for the ") + which + "-band peak of " + group + " (" +
                                std::to_string(law.points) + " runs; 0.5 = follows the contact frequency)");
      } catch (const cdpost::AnalysisError& e) {
        comparison.warnings.push_back(group + ": " + which + "-band peak fit: " + e.what());
      }
    };
    fit("contact", [](const ComparedRun& r) { return r.contact_peak; });
    fit("flow", [](const ComparedRun& r) { return r.flow_peak; });
  }
  for (const auto& r : comparison.runs)
    if (r.contact_peak && r.f_contact_hz)
      comparison.fits.add("contact_peak_ratio_" + r.label, r.contact_peak->frequency_hz / *r.f_contact_hz, "",
                          "contact-band peak / sqrt(2k/m)/(2 pi) for " + r.label);
}

}  // namespace

Comparison compare_runs(const CompareSettings& settings)
{
  if (settings.run_dirs.empty()) throw cdpost::AnalysisError("no run directory to compare");
  Comparison comparison;
  for (const auto& dir : settings.run_dirs) {
    if (settings.run.progress) std::fprintf(stderr, "cdref: analysing %s\n", dir.c_str());
    comparison.runs.push_back(analyse_one(dir, settings, comparison.warnings));
  }
  make_labels_unique(comparison.runs);
  fit_peak_shifts(comparison);
  return comparison;
}

}  // namespace cdref
