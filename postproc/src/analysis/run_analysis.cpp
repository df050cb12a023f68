#include "analysis/run_analysis.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <gsl/gsl_statistics_double.h>

#include "analysis/creep_results.h"
#include "analysis/layer_geometry.h"
#include "io/ave_chunk.h"
#include "io/ave_time.h"
#include "io/line_source.h"

namespace cdpost {

double Units::reduced_velocity_mps() const
{
  return std::sqrt(g_mps2 * d_m);
}
double Units::reduced_time_s() const
{
  return std::sqrt(d_m / g_mps2);
}
double Units::reduced_rate_hz() const
{
  return std::sqrt(g_mps2 / d_m);
}
void Units::use_reduced_input()
{
  length_unit_m = d_m;
  time_unit_s = reduced_time_s();
  input = Input::reduced;
}

std::string input_units_text(const Units& units)
{
  switch (units.input) {
    case Units::Input::si: return "input in SI units (m, s)";
    case Units::Input::reduced: return "input in reduced units (lengths in d, times in sqrt(d/g))";
    case Units::Input::custom: break;
  }
  std::ostringstream text;
  text << "input length unit " << units.length_unit_m << " m, time unit " << units.time_unit_s << " s";
  return text.str();
}

namespace {

// More unconverged steps than this fraction is a warning (the campaign refuses to publish such a run).
constexpr double kUnconvergedWarning = 1e-3;

std::string path_in(const RunSettings& settings, const std::string& file)
{
  return (std::filesystem::path(settings.directory) / file).string();
}

// Runs `step`, turning an AnalysisError into an InputError that names `file`.
template <class Step>
auto about_file(const std::string& file, Step step)
{
  try {
    return step();
  } catch (const AnalysisError& e) {
    throw InputError(file, 0, e.what());
  }
}

std::vector<double> scaled(const std::vector<double>& values, double factor)
{
  std::vector<double> out(values);
  for (double& v : out) v *= factor;
  return out;
}

std::vector<double> slice(const std::vector<double>& values, const Window& window)
{
  return {values.begin() + static_cast<long>(window.begin), values.begin() + static_cast<long>(window.end)};
}

// Spectra need one sampling interval: LAMMPS writes at a fixed Nfreq unless the deck changes it.
double regular_interval(const std::string& source, const std::vector<double>& time_s)
{
  if (time_s.size() < 2) throw InputError(source, 0, "fewer than 2 samples");
  const double interval = time_s[1] - time_s[0];
  for (size_t i = 1; i < time_s.size(); ++i) {
    double step = time_s[i] - time_s[i - 1];
    if (std::abs(step - interval) > 1e-6 * interval)
      throw InputError(source, 0,
                       "irregular sampling: interval " + std::to_string(step) + " s after " + std::to_string(interval) +
                           " s at t = " + std::to_string(time_s[i - 1]) + " s (spectra need a fixed output interval)");
  }
  return interval;
}

// Rows on the uniform grid (see TimeSeries): every interval must divide the grid, and every grid
// point must be there. The grid is the given sample rate's, counted from time 0, else the
// longest interval, counted from the first row. Other sampling is refused.
std::vector<size_t> coarse_rows(const ColumnTable& table, const std::vector<double>& time_s,
                                std::optional<double> sample_rate_hz)
{
  if (time_s.size() < 2) throw InputError(table.source, 0, "fewer than 2 samples");
  double longest = 0, finest = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < time_s.size(); ++i) {
    longest = std::max(longest, time_s[i] - time_s[i - 1]);
    finest = std::min(finest, time_s[i] - time_s[i - 1]);
  }
  const double coarse = sample_rate_hz ? 1.0 / *sample_rate_hz : longest;
  const double origin = sample_rate_hz ? 0.0 : time_s[0];
  if (longest > coarse * (1 + 1e-4))
    throw InputError(table.source, 0,
                     "sampling interval " + std::to_string(longest) + " s is longer than that of the sample rate, " +
                         std::to_string(coarse) + " s");
  // Times are printed rounded: tolerances well above rounding, well below the finest fraction.
  const double off_grid = 0.25 * finest / coarse;
  std::vector<size_t> kept;
  for (size_t i = 0; i < time_s.size(); ++i) {
    if (i > 0) {
      const double interval = time_s[i] - time_s[i - 1];
      const double parts = coarse / interval;
      if (!(interval > 0) || std::abs(parts - std::round(parts)) > 1e-4 * parts)
        throw InputError(table.source, table.row_lines[i],
                         "irregular sampling: interval " + std::to_string(interval) + " s does not divide " +
                             std::to_string(coarse) + " s (spectra need a fixed output interval)");
    }
    const double grid = (time_s[i] - origin) / coarse;
    if (std::abs(grid - std::round(grid)) < off_grid) kept.push_back(i);
  }
  if (kept.size() < 2) throw InputError(table.source, 0, "fewer than 2 samples on the grid of the sample rate");
  return kept;
}

std::vector<double> rows_of(const std::vector<double>& values, const std::vector<size_t>& rows)
{
  std::vector<double> out;
  out.reserve(rows.size());
  for (size_t r : rows) out.push_back(values[r]);
  return out;
}

std::vector<double> time_in_seconds(const ColumnTable& table, const RunSettings& settings)
{
  const auto& c = settings.columns;
  const double unit = settings.units.time_unit_s;
  if (table.has(c.time)) return scaled(table.column(c.time), unit);
  if (!settings.timestep_size)
    throw InputError(table.source, 0,
                     "no time column '" + c.time +
                         "': give --dt (the time step in input time units) so that time = " + c.timestep + " * dt");
  return scaled(table.column(c.timestep), *settings.timestep_size * unit);
}

std::optional<std::vector<double>> optional_column(const ColumnTable& table, const std::string& name, double factor,
                                                   std::vector<std::string>& warnings, const std::string& consequence)
{
  if (table.has(name)) return scaled(table.column(name), factor);
  warnings.push_back(table.source + ": no column '" + name + "': " + consequence);
  return std::nullopt;
}

TimeSeries read_time_series(const RunSettings& settings, std::vector<std::string>& warnings)
{
  const auto& c = settings.columns;
  auto table = read_ave_time(path_in(settings, c.time_file));
  const double velocity = settings.units.velocity_unit_mps();
  const std::vector<double> all_times = time_in_seconds(table, settings);
  const std::vector<size_t> rows = coarse_rows(table, all_times, settings.sample_rate_hz);
  auto kept = [&](const std::vector<double>& column) { return rows_of(column, rows); };
  TimeSeries series;
  series.rows_read = all_times.size();
  series.time_s = kept(all_times);
  series.timestep = kept(table.column(c.timestep));
  series.sample_interval_s = regular_interval(table.source, series.time_s);
  series.u_flow_mps = kept(scaled(table.column(c.u_flow), velocity));
  series.v_flow_mps = kept(scaled(table.column(c.v_flow), velocity));
  series.u_all_mps = optional_column(table, c.u_all, velocity, warnings, "u(t) of all grains not reported");
  if (series.u_all_mps) series.u_all_mps = kept(*series.u_all_mps);
  series.phi = optional_column(table, c.phi, 1.0, warnings, "phi not reported");
  if (series.phi) series.phi = kept(*series.phi);
  if (table.has(c.h)) series.h_m = kept(scaled(table.column(c.h), settings.units.length_unit_m));
  if (rows.size() < all_times.size())
    warnings.push_back(table.source + ": " + std::to_string(all_times.size() - rows.size()) +
                       " samples between the uniform ones (the step was refined) left out of the spectra");
  return series;
}

// Time (s) of a TimeStep: linear between the time file's samples, where the step is constant.
double time_of_step(const TimeSeries& series, double step)
{
  const auto& steps = series.timestep;
  auto upper = std::upper_bound(steps.begin(), steps.end(), step);
  size_t i = static_cast<size_t>(upper - steps.begin());
  i = std::clamp<size_t>(i, 1, steps.size() - 1);
  const double rate = (series.time_s[i] - series.time_s[i - 1]) / (steps[i] - steps[i - 1]);
  return series.time_s[i - 1] + (step - steps[i - 1]) * rate;
}

Window given_window(const RunSettings& settings, const std::vector<double>& time_s)
{
  const double unit = settings.units.time_unit_s;
  double start = settings.t_start ? *settings.t_start * unit : time_s.front();
  double end = settings.t_end ? *settings.t_end * unit : time_s.back();
  return window_between(time_s, start, end);
}

Window choose_window(const RunSettings& settings, const TimeSeries& series, bool& detected, const std::string& file)
{
  detected = !settings.t_start && !settings.t_end;
  return about_file(file, [&] {
    if (detected) return detect_stationary(series.time_s, series.u_flow_mps, settings.criterion);
    return given_window(settings, series.time_s);
  });
}

std::string percent(double fraction)
{
  std::ostringstream text;
  text << std::setprecision(2) << 100 * fraction << "%";
  return text.str();
}

// A window given on the command line is analysed whatever its drift; one that fails the test the
// detection applies (the drift of U across it within --max-drift) is labelled so and warned of.
void test_stationarity(RunAnalysis& run)
{
  const auto& s = run.series;
  const double drift = relative_drift(s.time_s, s.u_flow_mps, run.window);
  const double limit = run.settings.criterion.max_relative_drift;
  run.window_stationary = drift <= limit;
  run.window_drift = "U drifts by " + percent(drift) + " across it, " + (run.window_stationary ? "within" : "above") +
                     " the " + percent(limit) + " the stationarity test allows (--max-drift)";
  if (run.window_stationary) return;
  auto bounds = [&](double unit) {
    return format_estimate(s.time_s[run.window.begin] / unit, std::nullopt) + " to " +
           format_estimate(s.time_s[run.window.end - 1] / unit, std::nullopt);
  };
  run.warnings.push_back("the window t = " + bounds(1.0) + " s (" + bounds(run.settings.units.reduced_time_s()) +
                         " sqrt(d/g)) is not stationary: " + run.window_drift +
                         "; its means, spectra and profile are those of a changing flow");
}

// Blocks of a chunk file whose time lies in [t0, t1].
std::vector<size_t> blocks_between(const ChunkSeries& chunks, const TimeSeries& clock, double t0, double t1)
{
  std::vector<size_t> blocks;
  const double tolerance = 1e-9 * (std::abs(t1) + clock.sample_interval_s);
  for (size_t b = 0; b < chunks.blocks(); ++b) {
    double t = time_of_step(clock, chunks.timesteps[b]);
    if (t >= t0 - tolerance && t <= t1 + tolerance) blocks.push_back(b);
  }
  return blocks;
}

// Duration (s) each block averages: from the previous block's time (the first block: as long
// as the second). Blocks of a run whose step was refined are shorter.
std::vector<double> block_durations(const ChunkSeries& chunks, const TimeSeries& clock)
{
  std::vector<double> durations(chunks.blocks(), 1.0);
  if (chunks.blocks() < 2) return durations;
  for (size_t b = 1; b < chunks.blocks(); ++b)
    durations[b] = time_of_step(clock, chunks.timesteps[b]) - time_of_step(clock, chunks.timesteps[b - 1]);
  const double first = chunks.timesteps[0], before_first = first - (chunks.timesteps[1] - first);
  durations[0] = time_of_step(clock, first) - time_of_step(clock, before_first);
  return durations;
}

// Time average over the blocks, each weighted by the duration it covers (block_durations).
VelocityProfile average_profile(const ChunkSeries& chunks, const std::vector<size_t>& blocks,
                                const std::vector<double>& durations, const RunSettings& settings)
{
  const auto& c = settings.columns;
  const size_t coord = chunks.column_index(c.profile_coord), vx = chunks.column_index(c.profile_vx);
  const size_t count = chunks.column_index(c.profile_count);
  const double to_d = settings.units.length_unit_m / settings.units.d_m;
  const double to_reduced = settings.units.velocity_unit_mps() / settings.units.reduced_velocity_mps();
  VelocityProfile profile;
  for (size_t chunk = 0; chunk < chunks.chunks; ++chunk) {
    double weight = 0, momentum = 0, duration = 0;
    for (size_t b : blocks) {
      weight += durations[b] * chunks.value(b, chunk, count);
      momentum += durations[b] * chunks.value(b, chunk, count) * chunks.value(b, chunk, vx);
      duration += durations[b];
    }
    if (weight <= 0) continue;  // empty bin (above the surface): no velocity to report
    profile.z_d.push_back((chunks.value(blocks.front(), chunk, coord) - settings.z0) * to_d);
    profile.u_reduced.push_back(momentum / weight * to_reduced);
    profile.count.push_back(weight / duration);
  }
  if (profile.z_d.size() >= 2) profile.bin_width_d = std::abs(profile.z_d[1] - profile.z_d[0]);
  return profile;
}

// phi(z) of every bin, a time average over the blocks weighted by the duration each covers.
PackingProfile average_packing(const ChunkSeries& chunks, const std::vector<size_t>& blocks,
                               const std::vector<double>& durations, const RunSettings& settings)
{
  const size_t coord = chunks.column_index(settings.columns.packing_coord);
  const size_t phi = chunks.column_index(settings.columns.packing_phi);
  const double to_d = settings.units.length_unit_m / settings.units.d_m;
  PackingProfile profile;
  for (size_t chunk = 0; chunk < chunks.chunks; ++chunk) {
    double sum = 0, duration = 0;
    for (size_t b : blocks) sum += durations[b] * chunks.value(b, chunk, phi), duration += durations[b];
    profile.z_d.push_back((chunks.value(blocks.front(), chunk, coord) - settings.z0) * to_d);
    profile.phi.push_back(sum / duration);
  }
  return profile;
}

// phi of each bin of u(z), from the packing profile's bin at the same height.
std::vector<double> packing_of_bins(const VelocityProfile& velocity, const PackingProfile& packing,
                                    const std::string& source)
{
  std::vector<double> phi;
  for (double z : velocity.z_d) {
    auto same =
        std::find_if(packing.z_d.begin(), packing.z_d.end(), [&](double zp) { return std::abs(zp - z) < 1e-6; });
    if (same == packing.z_d.end())
      throw InputError(
          source, 0,
          "no bin at z = " + std::to_string(z) + " d, where profile.chunk has one (both need the same bins)");
    phi.push_back(packing.phi[static_cast<size_t>(same - packing.z_d.begin())]);
  }
  return phi;
}

// Layer top: the highest bin above z = 0 still holding half the median count of the
// occupied bins above z = 0.
std::optional<Estimate> thickness_from_profile(const VelocityProfile& profile)
{
  std::vector<double> counts;
  for (size_t i = 0; i < profile.z_d.size(); ++i)
    if (profile.z_d[i] > 0) counts.push_back(profile.count[i]);
  if (counts.size() < 3) return std::nullopt;
  std::sort(counts.begin(), counts.end());
  const double threshold = 0.5 * counts[counts.size() / 2];
  double top = 0;
  for (size_t i = 0; i < profile.z_d.size(); ++i)
    if (profile.z_d[i] > 0 && profile.count[i] >= threshold) top = std::max(top, profile.z_d[i]);
  return Estimate{top + 0.5 * profile.bin_width_d, 0.5 * profile.bin_width_d};
}

void add_spectrum_results(ResultTable& results, const Spectrum& spectrum, const SpectralPeak& peak,
                          const RunSettings& settings, const std::string& unit)
{
  results.add("f", Estimate{peak.frequency_hz, peak.frequency_error_hz}, "Hz",
              "peak frequency of v(t); error = half width at half power");
  results.add("A", peak.amplitude, unit, "spectral amplitude of v(t) at the peak");
  results.add(
      "A_mean", mean_amplitude_above(spectrum, settings.high_frequency_hz), unit,
      "mean spectral amplitude of v(t) at f >= " + format_estimate(settings.high_frequency_hz, std::nullopt) + " Hz");
  results.add("spectrum_resolution", spectrum.resolution_hz, "Hz", "frequency resolution (1 / segment duration)");
  results.add("spectrum_segments", spectrum.segments, "", "Hann-windowed segments averaged (Welch)");
}

struct Analyser {
  RunAnalysis& run;
  const RunSettings& settings;
  const Units& units;

  std::string time_path() const { return path_in(settings, settings.columns.time_file); }
  double reduced_velocity(double mps) const { return mps / units.reduced_velocity_mps(); }
  double reduced_time(double s) const { return s / units.reduced_time_s(); }

  Estimate window_mean(const std::vector<double>& values, double factor) const
  {
    auto estimate = about_file(
        time_path(), [&] { return block_mean(values, run.window.begin, run.window.end, settings.averaging_blocks); });
    estimate.value *= factor;
    if (estimate.error) *estimate.error *= factor;
    return estimate;
  }

  void time_averages()
  {
    const auto& s = run.series;
    auto& r = run.results;
    r.add("t_start", reduced_time(s.time_s[run.window.begin]), "sqrt(d/g)",
          run.window_detected ? "start of the detected stationary regime" : "start of the given " + window_name(run));
    r.add("t_end", reduced_time(s.time_s[run.window.end - 1]), "sqrt(d/g)", "end of the " + window_name(run));
    r.add("stationary_drift", relative_drift(s.time_s, s.u_flow_mps, run.window), "",
          "drift of the line fitted to U(t) across the window, relative to its mean");
    r.add("U", window_mean(s.u_flow_mps, 1 / units.reduced_velocity_mps()), "sqrt(g d)",
          "mean x-velocity of the grains with z > 0");
    if (s.u_all_mps)
      r.add("u_all", window_mean(*s.u_all_mps, 1 / units.reduced_velocity_mps()), "sqrt(g d)",
            "mean x-velocity of all grains");
    if (s.phi) r.add("phi", window_mean(*s.phi, 1.0), "", "area fraction of the flowing layer");
    if (s.h_m)
      r.add("h", window_mean(*s.h_m, 1 / units.d_m), "d", "flowing-layer thickness (from " + settings.columns.h + ")");
  }

  void spectrum_of_v()
  {
    auto v = scaled(slice(run.series.v_flow_mps, run.window), 1 / units.reduced_velocity_mps());
    about_file(time_path(), [&] {
      run.spectrum = amplitude_spectrum(v, run.series.sample_interval_s, settings.spectrum);
      run.peak = find_peak(run.spectrum, settings.peak_fmin_hz, settings.peak_fmax_hz);
      add_spectrum_results(run.results, run.spectrum, run.peak, settings, "sqrt(g d)");
      return 0;
    });
  }

  std::optional<ChunkSeries> read_optional_chunks(const std::string& file, const std::string& consequence)
  {
    const auto path = path_in(settings, file);
    if (!std::filesystem::exists(path)) {
      run.warnings.push_back(path + " not found: " + consequence);
      return std::nullopt;
    }
    return read_ave_chunk(path);
  }

  std::vector<size_t> window_blocks(const ChunkSeries& chunks) const
  {
    auto blocks =
        blocks_between(chunks, run.series, run.series.time_s[run.window.begin], run.series.time_s[run.window.end - 1]);
    if (blocks.empty()) throw InputError(chunks.source, 0, "no output block inside the stationary window");
    return blocks;
  }

  // The blocks of a per-sample chunk file (layers.chunk) on the time file's uniform grid.
  std::vector<size_t> uniform_blocks(const ChunkSeries& chunks, const std::vector<size_t>& blocks) const
  {
    std::vector<size_t> kept;
    const double t0 = run.series.time_s.front(), interval = run.series.sample_interval_s;
    for (size_t b : blocks) {
      const double grid = (time_of_step(run.series, chunks.timesteps[b]) - t0) / interval;
      if (std::abs(grid - std::round(grid)) < 1e-6) kept.push_back(b);  // exact: from TimeStep
    }
    return kept;
  }

  void profile()
  {
    auto chunks = read_optional_chunks(settings.columns.profile_file, "no u(z), Bagnold or creep fit");
    if (!chunks) return;
    run.profile = average_profile(*chunks, window_blocks(*chunks), block_durations(*chunks, run.series), settings);
    if (!run.series.h_m) {
      if (auto h = thickness_from_profile(*run.profile))
        run.results.add("h", *h, "d", "flowing-layer thickness: top of the bins holding half the median count");
    }
    const auto* h = run.results.find("h");
    if (!h) return;
    run.h_d = h->value;
    fit_profile(chunks->source);
  }

  // phi(z) from packing.chunk over the window, in profile.csv and as phi_bulk, h_packing, I_packing.
  void packing()
  {
    auto chunks = read_optional_chunks(settings.columns.packing_file, "no phi(z), phi_bulk or h_packing");
    if (!chunks) return;
    run.packing = average_packing(*chunks, window_blocks(*chunks), block_durations(*chunks, run.series), settings);
    if (run.profile) run.profile->phi = packing_of_bins(*run.profile, *run.packing, chunks->source);
    if (auto problem = add_layer_geometry(run.results, *run.packing, "packing.chunk"))
      run.warnings.push_back(chunks->source + ": " + *problem);
  }

  void fit_profile(const std::string& file)
  {
    const auto& p = *run.profile;
    try {
      run.bagnold = fit_bagnold(p.z_d, p.u_reduced, run.h_d);
      run.results.add("bagnold_slip", run.bagnold->slip, "sqrt(g d)",
                      "u(0) of the Bagnold fit u = slip + a (h^1.5 - (h-z)^1.5)");
      run.results.add("bagnold_amplitude", run.bagnold->amplitude, "sqrt(g d)/d^1.5", "a of the Bagnold fit");
      run.results.add("bagnold_r2", run.bagnold->r_squared, "", "coefficient of determination of the Bagnold fit");
    } catch (const AnalysisError& e) {
      run.warnings.push_back(file + ": Bagnold fit skipped: " + e.what());
    }
    run.creep = measure_creep(p.z_d, p.u_reduced, settings.creep);
    add_creep_results(run.results, *run.creep);
    for (const auto& problem : creep_problems(*run.creep)) run.warnings.push_back(file + ": creep " + problem);
  }

  void derived_rates()
  {
    if (run.h_d <= 0) {
      run.warnings.push_back("no layer thickness h (no column " + settings.columns.h +
                             " and no profile): U/h and I not reported");
      return;
    }
    const auto& U = *run.results.find("U");
    const double rate_reduced = U.value / run.h_d;  // sqrt(g/d)
    const double h_error = run.results.find("h")->error.value_or(0);
    auto relative = [&](double power) {  // relative error of U / h^power
      return std::hypot(U.error.value_or(0) / U.value, power * h_error / run.h_d);
    };
    run.results.add(
        "shear_rate",
        Estimate{rate_reduced * units.reduced_rate_hz(), rate_reduced * units.reduced_rate_hz() * relative(1)}, "1/s",
        "U/h");
    run.results.add("shear_rate_reduced", Estimate{rate_reduced, rate_reduced * relative(1)}, "sqrt(g/d)", "U/h");
    const double inertial = U.value / std::pow(run.h_d, 1.5);
    run.results.add("I", Estimate{inertial, inertial * relative(1.5)}, "", "inertial number d U / (sqrt(g) h^1.5)");
    const double x = std::sqrt(units.reduced_rate_hz() * units.reduced_rate_hz() / U.value);
    run.results.add("f_scale", Estimate{x, 0.5 * x * U.error.value_or(0) / U.value}, "Hz", "(sqrt(g d)/U * g/d)^(1/2)");
  }

  // The samples of a per-sample chunk file inside the window, on the time file's grid, and their interval (s).
  std::pair<std::vector<size_t>, double> window_samples(const ChunkSeries& chunks) const
  {
    const auto blocks = uniform_blocks(chunks, window_blocks(chunks));
    if (blocks.size() < 2) throw InputError(chunks.source, 0, "fewer than 2 samples inside the stationary window");
    std::vector<double> times;
    for (size_t b : blocks) times.push_back(time_of_step(run.series, chunks.timesteps[b]));
    return {blocks, regular_interval(chunks.source, times)};
  }

  void layer_spectra()
  {
    auto chunks = read_optional_chunks(settings.columns.layers_file, "no depth-resolved spectra");
    if (!chunks) return;
    const auto& c = settings.columns;
    const size_t coord = chunks->column_index(c.layers_coord), vz = chunks->column_index(c.layers_vz);
    const auto [blocks, interval] = window_samples(*chunks);
    const double to_reduced = units.velocity_unit_mps() / units.reduced_velocity_mps();
    for (size_t chunk = 0; chunk < chunks->chunks; ++chunk) {
      if (chunks->has(c.layers_count) && mean_count(*chunks, blocks, chunk) < 0.5) continue;  // empty layer
      std::vector<double> v;
      for (size_t b : blocks) v.push_back(chunks->value(b, chunk, vz) * to_reduced);
      LayerSpectrum layer;
      layer.z_d = (chunks->value(blocks.front(), chunk, coord) - settings.z0) * units.length_unit_m / units.d_m;
      about_file(chunks->source, [&] {
        layer.spectrum = amplitude_spectrum(v, interval, settings.spectrum);
        layer.peak = find_peak(layer.spectrum, settings.peak_fmin_hz, settings.peak_fmax_hz);
        return 0;
      });
      layer.amplitude_at_f = amplitude_at(layer.spectrum, run.peak.frequency_hz);
      run.layers.push_back(layer);
    }
    run.results.add("layers", static_cast<double>(run.layers.size()), "", "layers with a depth-resolved spectrum");
  }

  void along_cell()
  {
    const std::string consequence = "no space-time spectrum or coherence along the cell";
    auto chunks = read_optional_chunks(settings.columns.columns_file, consequence);
    if (!chunks) return;
    if (!settings.cell_length_d) {
      run.warnings.push_back(chunks->source + ": no cell length (--cell-length, the deck's L in d): " + consequence);
      return;
    }
    const auto& c = settings.columns;
    const ColumnsLayout layout{chunks->column_index(c.columns_coord), chunks->column_index(c.columns_v),
                               chunks->column_index(c.columns_count)};
    const auto [blocks, interval] = window_samples(*chunks);
    try {
      size_t filled = 0;
      const double to_reduced = units.velocity_unit_mps() / units.reduced_velocity_mps();
      const auto field =
          field_from_chunks(*chunks, blocks, layout, to_reduced, interval, *settings.cell_length_d, filled);
      run.along_cell =
          analyse_along_cell(field, run.peak, settings.spectrum, units.reduced_rate_hz(), run.results, run.warnings);
      run.results.add("column_samples_filled", static_cast<double>(filled), "",
                      "samples of empty columns interpolated in time");
    } catch (const AnalysisError& e) {
      run.warnings.push_back(chunks->source + ": " + consequence + ": " + e.what());
    }
  }

  double mean_count(const ChunkSeries& chunks, const std::vector<size_t>& blocks, size_t chunk) const
  {
    const size_t count = chunks.column_index(settings.columns.layers_count);
    double sum = 0;
    for (size_t b : blocks) sum += chunks.value(b, chunk, count);
    return sum / static_cast<double>(blocks.size());
  }
};

}  // namespace

ColumnSpectrum analyse_column_spectrum(const std::string& path, const std::string& column, const RunSettings& settings)
{
  auto table = read_ave_time(path);
  const auto all_times = time_in_seconds(table, settings);
  const auto rows = coarse_rows(table, all_times, settings.sample_rate_hz);
  const auto time_s = rows_of(all_times, rows);
  const double interval = regular_interval(table.source, time_s);
  return about_file(path, [&] {
    auto window = given_window(settings, time_s);
    ColumnSpectrum result;
    result.spectrum =
        amplitude_spectrum(slice(rows_of(table.column(column), rows), window), interval, settings.spectrum);
    result.peak = find_peak(result.spectrum, settings.peak_fmin_hz, settings.peak_fmax_hz);
    result.results.add("t_start", time_s[window.begin], "s", "start of the analysed window");
    result.results.add("t_end", time_s[window.end - 1], "s", "end of the analysed window");
    add_spectrum_results(result.results, result.spectrum, result.peak, settings, "input");
    return result;
  });
}

std::string window_name(const RunAnalysis& run)
{
  return run.window_stationary ? "stationary window" : "window (not stationary)";
}

RunAnalysis analyse_run(const RunSettings& settings)
{
  RunAnalysis run;
  run.settings = settings;
  run.series = read_time_series(settings, run.warnings);
  run.window = choose_window(settings, run.series, run.window_detected, path_in(settings, settings.columns.time_file));
  test_stationarity(run);
  Analyser analyser{run, settings, settings.units};
  analyser.time_averages();
  analyser.spectrum_of_v();
  analyser.profile();
  if (run.h_d <= 0 && run.results.find("h")) run.h_d = run.results.find("h")->value;
  analyser.packing();
  analyser.derived_rates();
  analyser.layer_spectra();
  analyser.along_cell();
  run.solver = read_solver_record(settings.directory);
  add_solver_results(run.results, run.solver);
  if (!run.solver.health)
    run.warnings.push_back(run.solver.solver_file + " not found: the solver's health is not recorded");
  else if (run.solver.health->unconverged_fraction > kUnconvergedWarning)
    run.warnings.push_back(run.solver.solver_file + ": " + count_text(run.solver.health->unconverged_steps) +
                           " steps unconverged, " + format_estimate(100 * run.solver.health->unconverged_fraction, {}) +
                           " % of the steps (more than 0.1 %)");
  return run;
}

}  // namespace cdpost
