#include "comparison.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "fit/linear_fit.h"
#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/tokens.h"
#include "output/gnuplot.h"
#include "output/report.h"
#include "signal/stationary.h"

namespace cdref {

namespace fs = std::filesystem;
using cdpost::Curve;
using cdpost::CurveStyle;
using cdpost::Figure;
using cdpost::Panel;
using cdpost::format_estimate;

std::optional<double> ComparedRun::wall_per_physical_second() const {
  if (!loop_seconds || !physical_seconds || *physical_seconds <= 0) return std::nullopt;
  return *loop_seconds / *physical_seconds;
}

std::optional<double> ComparedRun::cpu_per_physical_second() const {
  auto wall = wall_per_physical_second();
  if (!wall) return std::nullopt;
  if (process_cpu_share) return *wall * std::min(1.0, *process_cpu_share);
  if (cpu_percent) return *wall * std::min(1.0, *cpu_percent / 100);
  return std::nullopt;
}

namespace {

std::string short_number(double x) { return format_estimate(x, std::nullopt); }

std::string code_name(const std::string& code) {
  if (code == "lammps-granular") return "LAMMPS GRANULAR";
  if (code == "liggghts") return "LIGGGHTS";
  if (code == "lmp_cd") return "lmp_cd";
  return code;
}

std::string make_label(const ComparedRun& run) {
  if (run.model == "rigid") {
    auto tolerance = run.info.text("tolerance");
    return "rigid" + (tolerance ? " tol " + *tolerance : std::string());
  }
  if (run.model == "unknown") return fs::path(run.directory).filename().string();
  std::string code = run.code == "lammps-granular" ? "granular" : run.code;
  auto overlap = run.info.text("overlap_target");
  return code + " " + run.model + (overlap ? " " + *overlap : std::string());
}

// Time (input units) and TimeStep of every sample of flow.time.
struct Samples {
  std::vector<double> time, timestep, u_flow;
};

Samples read_samples(const cdpost::RunSettings& s) {
  auto table = cdpost::read_ave_time((fs::path(s.directory) / s.columns.time_file).string());
  Samples samples;
  samples.timestep = table.column(s.columns.timestep);
  if (table.has(s.columns.time)) {
    samples.time = table.column(s.columns.time);
  } else if (s.timestep_size) {
    for (double step : samples.timestep) samples.time.push_back(step * *s.timestep_size);
  } else {
    throw cdpost::InputError(table.source, 0, "no time column '" + s.columns.time + "': give --dt");
  }
  samples.u_flow = table.column(s.columns.u_flow);
  return samples;
}

// Chooses the analysis window: the settings' override, else the detected stationary regime,
// else (flagged) the second half of the run.
void choose_window(ComparedRun& run, cdpost::RunSettings& s, const Samples& samples) {
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
    run.window_note = std::string("NOT STATIONARY (") + e.what() + "): analysed over the second half, t >= " +
                      short_number(*s.t_start);
  }
}

std::optional<std::string> find_log(const std::string& dir) {
  for (const char* name : {"log.lammps", "log.liggghts", "log.cd"})
    if (fs::exists(fs::path(dir) / name)) return (fs::path(dir) / name).string();
  return std::nullopt;
}

// (user + sys)/wall of a process from run_comparison.sh's timing.txt ("wall user sys").
std::optional<double> process_share(const fs::path& dir) {
  const auto timing = dir / "timing.txt";
  if (!fs::exists(timing)) return std::nullopt;
  cdpost::LineSource source(timing.string());
  std::string line;
  if (!source.next(line)) return std::nullopt;
  auto tokens = cdpost::split_whitespace(line);
  if (tokens.size() != 3) source.fail("expected 'wall user sys' seconds");
  const double wall = cdpost::parse_number(tokens[0], source, "wall");
  const double cpu = cdpost::parse_number(tokens[1], source, "user") + cdpost::parse_number(tokens[2], source, "sys");
  if (!(wall > 0)) return std::nullopt;
  return std::min(1.0, cpu / wall);
}

// The run's own flow stage (the last loop of its log) plus those of the continuation runs
// in its part2, part3, ... subdirectories (in.chute_rigid in parts).
void read_cost(ComparedRun& run, const Samples& samples, double time_unit_s, std::vector<std::string>& warnings) {
  if (samples.timestep.size() < 2) return;
  const double seconds_per_step = (samples.time.back() - samples.time.front()) /
                                  (samples.timestep.back() - samples.timestep.front()) * time_unit_s;
  double wall = 0, cpu = 0, physical = 0;
  bool cpu_known = true;
  for (int part = 1;; ++part) {
    const fs::path dir = part == 1 ? fs::path(run.directory) : fs::path(run.directory) / ("part" + std::to_string(part));
    if (part > 1 && !fs::is_directory(dir)) break;
    auto log = find_log(dir.string());
    auto loops = log ? read_loop_times(*log) : std::vector<LoopTime>{};
    if (loops.empty()) {
      warnings.push_back(run.label + ": no 'Loop time' in a log of " + dir.string() + ": no wall time");
      return;
    }
    const auto& flow = loops.back();
    wall += flow.seconds;
    physical += flow.steps * seconds_per_step;
    auto share = process_share(dir);
    if (!share && flow.cpu_percent) share = std::min(1.0, *flow.cpu_percent / 100);
    if (share)
      cpu += flow.seconds * *share;
    else
      cpu_known = false;
    if (part == 1) run.cpu_percent = flow.cpu_percent;
  }
  run.loop_seconds = wall;
  run.physical_seconds = physical;
  if (cpu_known && wall > 0) run.process_cpu_share = cpu / wall;
}

void read_overlaps(ComparedRun& run, const CompareSettings& settings, const cdpost::RunSettings& s, const Samples& samples,
                   std::vector<std::string>& warnings) {
  const auto dump = fs::path(run.directory) / settings.dump_name;
  if (!fs::exists(dump)) {
    warnings.push_back(run.label + ": no " + settings.dump_name + ": overlaps not measured");
    return;
  }
  const auto& w = run.analysis.window;
  OverlapOptions options;
  options.mean_diameter = s.units.d_m / s.units.length_unit_m;
  options.first_timestep = static_cast<long>(samples.timestep[w.begin]);
  options.last_timestep = static_cast<long>(samples.timestep[w.end - 1]);
  try {
    run.overlaps = dump_overlaps(dump.string(), options);
  } catch (const cdpost::InputError& e) {
    warnings.push_back(run.label + ": overlaps not measured: " + e.what());
  }
}

// The highest bin in [lo, hi] if it is a peak: a bin inside the band, not at one of its ends
// (the maximum of a spectrum that only falls through the band sits at its lower end).
std::optional<cdpost::SpectralPeak> band_peak(const cdpost::Spectrum& spectrum, double lo, double hi) {
  if (!(lo < hi)) return std::nullopt;
  const auto& f = spectrum.frequency_hz;
  const auto& a = spectrum.amplitude;
  size_t first = static_cast<size_t>(std::lower_bound(f.begin(), f.end(), lo) - f.begin());
  size_t end = static_cast<size_t>(std::upper_bound(f.begin(), f.end(), hi) - f.begin());
  if (end < first + 3) return std::nullopt;
  size_t top = static_cast<size_t>(std::max_element(a.begin() + static_cast<long>(first), a.begin() + static_cast<long>(end)) - a.begin());
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
std::optional<BandExcess> band_excess(const cdpost::Spectrum& spectrum, double lo, double hi, double smoothing) {
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

void find_band_peaks(ComparedRun& run, const CompareSettings& settings) {
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
  run.contact_peak = cdpost::find_peak(spectrum, std::max(lo, excess->frequency_hz - half), std::min(hi, excess->frequency_hz + half));
}

ComparedRun analyse_one(const std::string& dir, const CompareSettings& settings, std::vector<std::string>& warnings) {
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

void make_labels_unique(std::vector<ComparedRun>& runs) {
  std::map<std::string, int> seen;
  for (const auto& r : runs) ++seen[r.label];
  for (auto& r : runs)
    if (seen[r.label] > 1) r.label += " (" + fs::path(r.directory).filename().string() + ")";
}

// How the soft runs' peaks move with k: f = c k^n per code and model, for the contact-band
// peak and the flow-band peak.
void fit_peak_shifts(Comparison& comparison) {
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

Comparison compare_runs(const CompareSettings& settings) {
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

// ---- output ----------------------------------------------------------------------------------

namespace {

std::string cell(const std::optional<double>& value, const std::optional<double>& error = std::nullopt) {
  return value ? format_estimate(*value, error) : std::string("-");
}

std::optional<double> result_value(const ComparedRun& r, const std::string& name) {
  if (const auto* row = r.analysis.results.find(name)) return row->value;
  return std::nullopt;
}
std::optional<double> result_error(const ComparedRun& r, const std::string& name) {
  if (const auto* row = r.analysis.results.find(name)) return row->error;
  return std::nullopt;
}

struct Column {
  std::string name, unit;
  std::function<std::optional<double>(const ComparedRun&)> value;
  std::function<std::optional<double>(const ComparedRun&)> error;
};

std::vector<Column> table_columns() {
  auto none = [](const ComparedRun&) -> std::optional<double> { return std::nullopt; };
  auto result = [](const std::string& name) {
    return [name](const ComparedRun& r) { return result_value(r, name); };
  };
  auto result_err = [](const std::string& name) {
    return [name](const ComparedRun& r) { return result_error(r, name); };
  };
  return {
      {"k", "m g/d", [](const ComparedRun& r) { return r.k_reduced; }, none},
      {"f_contact", "Hz", [](const ComparedRun& r) { return r.f_contact_hz; }, none},
      {"overlap_target", "d", [](const ComparedRun& r) { return r.overlap_target; }, none},
      {"overlap_mean", "d", [](const ComparedRun& r) { return r.overlaps ? std::optional<double>(r.overlaps->mean) : std::nullopt; }, none},
      {"overlap_max", "d", [](const ComparedRun& r) { return r.overlaps ? std::optional<double>(r.overlaps->max) : std::nullopt; }, none},
      {"U", "sqrt(g d)", result("U"), result_err("U")},
      {"phi", "", result("phi"), result_err("phi")},
      {"h", "d", result("h"), result_err("h")},
      {"f", "Hz", result("f"), result_err("f")},
      {"A", "sqrt(g d)", result("A"), none},
      {"f_flow", "Hz", [](const ComparedRun& r) { return r.flow_peak ? std::optional<double>(r.flow_peak->frequency_hz) : std::nullopt; },
       [](const ComparedRun& r) { return r.flow_peak ? std::optional<double>(r.flow_peak->frequency_error_hz) : std::nullopt; }},
      {"A_flow", "sqrt(g d)", [](const ComparedRun& r) { return r.flow_peak ? std::optional<double>(r.flow_peak->amplitude) : std::nullopt; }, none},
      {"f_contact_band", "Hz",
       [](const ComparedRun& r) { return r.contact_peak ? std::optional<double>(r.contact_peak->frequency_hz) : std::nullopt; },
       [](const ComparedRun& r) { return r.contact_peak ? std::optional<double>(r.contact_peak->frequency_error_hz) : std::nullopt; }},
      {"A_contact_band", "sqrt(g d)",
       [](const ComparedRun& r) { return r.contact_peak ? std::optional<double>(r.contact_peak->amplitude) : std::nullopt; }, none},
      {"contact_excess", "", [](const ComparedRun& r) { return r.contact_excess; }, none},
      {"A_mean", "sqrt(g d)", result("A_mean"), none},
      {"wall_per_physical_s", "s/s", [](const ComparedRun& r) { return r.wall_per_physical_second(); }, none},
      {"cpu_per_physical_s", "s/s", [](const ComparedRun& r) { return r.cpu_per_physical_second(); }, none},
  };
}

std::string csv_text(const std::optional<double>& x) {
  if (!x) return "";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.8g", *x);
  return buffer;
}

void write_table_csv(const Comparison& c, const std::string& path) {
  auto out = cdpost::open_output(path);
  const auto columns = table_columns();
  out << "run,label,code,model,stationary";
  for (const auto& col : columns) out << ',' << col.name << (col.unit.empty() ? "" : "_" + col.unit) << ",error";
  out << '\n';
  for (const auto& r : c.runs) {
    out << '"' << r.directory << "\",\"" << r.label << "\"," << r.code << ',' << r.model << ',' << (r.stationary ? 1 : 0);
    for (const auto& col : columns) out << ',' << csv_text(col.value(r)) << ',' << csv_text(col.error(r));
    out << '\n';
  }
}

std::string markdown_table(const Comparison& c) {
  const auto columns = table_columns();
  std::ostringstream out;
  out << "| run | model |";
  for (const auto& col : columns) out << ' ' << col.name << (col.unit.empty() ? "" : " (" + col.unit + ")") << " |";
  out << "\n|---|---|";
  for (size_t i = 0; i < columns.size(); ++i) out << "---|";
  out << '\n';
  for (const auto& r : c.runs) {
    out << "| " << r.label << (r.stationary ? "" : " (not stationary)") << " | " << code_name(r.code) << ' ' << r.model << " |";
    for (const auto& col : columns) out << ' ' << cell(col.value(r), col.error(r)) << " |";
    out << '\n';
  }
  return out.str();
}

Curve curve(const std::string& title, CurveStyle style, std::vector<double> x, std::vector<double> y) {
  Curve c;
  c.title = title;
  c.style = style;
  c.x = std::move(x);
  c.y = std::move(y);
  return c;
}

// Spectra of v(t) on log-log axes, with a vertical line at each soft run's contact frequency.
Figure spectra_figure(const std::vector<const ComparedRun*>& runs, const std::string& name, const std::string& title) {
  Panel panel;
  panel.title = title;
  panel.x_label = "f (Hz)";
  panel.y_label = "A / sqrt(g d)";
  panel.log_x = panel.log_y = true;
  panel.key = "outside right top";
  double lo = INFINITY, hi = 0;
  for (const auto* r : runs) {
    std::vector<double> f, a;
    const auto& s = r->analysis.spectrum;
    for (size_t k = 1; k < s.frequency_hz.size(); ++k)
      if (s.amplitude[k] > 0) {
        f.push_back(s.frequency_hz[k]);
        a.push_back(s.amplitude[k]);
        lo = std::min(lo, s.amplitude[k]);
        hi = std::max(hi, s.amplitude[k]);
      }
    panel.curves.push_back(curve(r->label, CurveStyle::Lines, f, a));
  }
  if (hi > 0)
    for (const auto* r : runs)
      if (r->f_contact_hz)
        panel.curves.push_back(curve("f_c " + r->label + " = " + short_number(*r->f_contact_hz) + " Hz", CurveStyle::Lines,
                                     {*r->f_contact_hz, *r->f_contact_hz}, {lo, hi}));
  return {name, title, {panel}, 1200, 650};
}

Figure peaks_figure(const Comparison& c) {
  Panel panel;
  panel.title = "Spectral peaks against stiffness (lines: sqrt(2k/m)/(2 pi); rigid runs drawn flat)";
  panel.x_label = "k / (m g / d)";
  panel.y_label = "f (Hz)";
  panel.log_x = panel.log_y = true;
  panel.key = "outside right top";
  std::map<std::string, std::pair<Curve, Curve>> by_group;
  double kmin = INFINITY, kmax = 0;
  std::optional<double> k_to_f;  // f_c / sqrt(k_reduced), the same for every soft run of one d
  for (const auto& r : c.runs) {
    if (!r.soft() || !r.k_reduced) continue;
    kmin = std::min(kmin, *r.k_reduced);
    kmax = std::max(kmax, *r.k_reduced);
    k_to_f = *r.f_contact_hz / std::sqrt(*r.k_reduced);
    auto& [contact, flow] = by_group[code_name(r.code) + " " + r.model];
    contact.style = flow.style = CurveStyle::ErrorBars;
    if (r.contact_peak) {
      contact.x.push_back(*r.k_reduced);
      contact.y.push_back(r.contact_peak->frequency_hz);
      contact.y_error.push_back(r.contact_peak->frequency_error_hz);
    }
    if (r.flow_peak) {
      flow.x.push_back(*r.k_reduced);
      flow.y.push_back(r.flow_peak->frequency_hz);
      flow.y_error.push_back(r.flow_peak->frequency_error_hz);
    }
  }
  for (auto& [group, curves] : by_group) {
    curves.first.title = group + ": contact-band peak";
    curves.second.title = group + ": flow-band peak";
    if (!curves.first.x.empty()) panel.curves.push_back(curves.first);
    if (!curves.second.x.empty()) panel.curves.push_back(curves.second);
  }
  if (k_to_f && kmax > 0) {
    std::vector<double> k{kmin / 2, kmax * 2};
    panel.curves.push_back(curve("sqrt(2k/m)/(2 pi)", CurveStyle::Lines, k, {*k_to_f * std::sqrt(k[0]), *k_to_f * std::sqrt(k[1])}));
    for (const auto& r : c.runs)
      if (r.model == "rigid" && r.flow_peak)
        panel.curves.push_back(curve(r.label + ": flow-band peak", CurveStyle::Lines, k,
                                     {r.flow_peak->frequency_hz, r.flow_peak->frequency_hz}));
  }
  return {"peaks_vs_k", "Where the spectral peaks sit as k changes", {panel}, 1100, 650};
}

Figure bulk_figure(const Comparison& c) {
  Figure figure{"bulk_vs_k", "U, phi and h of every run against stiffness (rigid runs drawn flat)", {}, 900, 1000};
  const char* names[3] = {"U", "phi", "h"};
  const char* labels[3] = {"U / sqrt(g d)", "phi", "h / d"};
  double kmin = INFINITY, kmax = 0;
  for (const auto& r : c.runs)
    if (r.k_reduced) {
      kmin = std::min(kmin, *r.k_reduced);
      kmax = std::max(kmax, *r.k_reduced);
    }
  if (!(kmax > 0)) return figure;
  for (int i = 0; i < 3; ++i) {
    Panel p;
    p.title = names[i];
    p.x_label = "k / (m g / d)";
    p.y_label = labels[i];
    p.log_x = true;
    p.key = "outside right top";
    p.height = 1.0 / 3;
    p.origin_y = (2 - i) / 3.0;
    std::map<std::string, Curve> groups;
    for (const auto& r : c.runs) {
      auto v = result_value(r, names[i]);
      if (!v) continue;
      if (r.model == "rigid" || !r.k_reduced) {
        p.curves.push_back(curve(r.label, CurveStyle::Lines, {kmin / 2, kmax * 2}, {*v, *v}));
        continue;
      }
      auto& g = groups[code_name(r.code) + " " + r.model];
      g.title = code_name(r.code) + " " + r.model;
      g.style = CurveStyle::ErrorBars;
      g.x.push_back(*r.k_reduced);
      g.y.push_back(*v);
      g.y_error.push_back(result_error(r, names[i]).value_or(0));
    }
    for (auto& [name, g] : groups) p.curves.push_back(g);
    if (!p.curves.empty()) figure.panels.push_back(p);
  }
  return figure;
}

Figure profiles_figure(const Comparison& c) {
  Panel panel;
  panel.title = "Velocity profiles u(z) over each run's window";
  panel.x_label = "u / sqrt(g d)";
  panel.y_label = "z / d";
  panel.key = "outside right top";
  for (const auto& r : c.runs)
    if (r.analysis.profile) panel.curves.push_back(curve(r.label, CurveStyle::LinesPoints, r.analysis.profile->u_reduced, r.analysis.profile->z_d));
  return {"profiles", "u(z) of every run", {panel}, 1100, 700};
}

Figure u_t_figure(const Comparison& c) {
  Panel panel;
  panel.title = "U(t): mean x-velocity of the grains with z > 0";
  panel.x_label = "t / sqrt(d/g)";
  panel.y_label = "U / sqrt(g d)";
  panel.key = "outside right top";
  for (const auto& r : c.runs) {
    const auto& u = r.analysis.settings.units;
    std::vector<double> t, v;
    const auto& s = r.analysis.series;
    const size_t stride = std::max<size_t>(1, s.time_s.size() / 2000);
    for (size_t i = 0; i < s.time_s.size(); i += stride) {
      t.push_back(s.time_s[i] / u.reduced_time_s());
      v.push_back(s.u_flow_mps[i] / u.reduced_velocity_mps());
    }
    panel.curves.push_back(curve(r.label, CurveStyle::Lines, t, v));
  }
  return {"u_t", "U(t) of every run", {panel}, 1100, 600};
}

Figure cost_figure(const Comparison& c) {
  Panel panel;
  panel.title = "Cost per physical second: wall time, and wall time x the process's CPU share (rigid: flat lines)";
  panel.x_label = "k / (m g / d)";
  panel.y_label = "s / physical s";
  panel.log_x = panel.log_y = true;
  panel.key = "outside right top";
  double kmin = INFINITY, kmax = 0;
  for (const auto& r : c.runs)
    if (r.k_reduced) {
      kmin = std::min(kmin, *r.k_reduced);
      kmax = std::max(kmax, *r.k_reduced);
    }
  using Metric = std::optional<double> (ComparedRun::*)() const;
  const std::pair<const char*, Metric> metrics[2] = {{"wall", &ComparedRun::wall_per_physical_second},
                                                     {"CPU", &ComparedRun::cpu_per_physical_second}};
  for (const auto& [metric, cost_of] : metrics) {
    std::map<std::string, std::vector<std::pair<double, double>>> groups;
    for (const auto& r : c.runs) {
      auto cost = (r.*cost_of)();
      if (!cost) continue;
      if (!r.k_reduced) {
        if (kmax > 0) panel.curves.push_back(curve(r.label + " " + metric, CurveStyle::Lines, {kmin / 2, kmax * 2}, {*cost, *cost}));
        continue;
      }
      groups[code_name(r.code) + " " + r.model].push_back({*r.k_reduced, *cost});
    }
    for (auto& [name, points] : groups) {
      std::sort(points.begin(), points.end());
      std::vector<double> k, cost;
      for (const auto& [x, y] : points) {
        k.push_back(x);
        cost.push_back(y);
      }
      panel.curves.push_back(curve(name + " " + metric, CurveStyle::LinesPoints, k, cost));
    }
  }
  return {"cost", "Cost of each model", {panel}, 1100, 600};
}

void write_long_csvs(const Comparison& c, const std::string& out) {
  auto spectra = cdpost::open_output(out + "/spectra.csv");
  spectra << "label,f_Hz,A_sqrt_gd\n";
  for (const auto& r : c.runs) {
    const auto& s = r.analysis.spectrum;
    for (size_t k = 0; k < s.frequency_hz.size(); ++k)
      spectra << '"' << r.label << "\"," << csv_text(s.frequency_hz[k]) << ',' << csv_text(s.amplitude[k]) << '\n';
  }
  auto profiles = cdpost::open_output(out + "/profiles.csv");
  profiles << "label,z_d,u_sqrt_gd,count\n";
  for (const auto& r : c.runs)
    if (r.analysis.profile) {
      const auto& p = *r.analysis.profile;
      for (size_t i = 0; i < p.z_d.size(); ++i)
        profiles << '"' << r.label << "\"," << csv_text(p.z_d[i]) << ',' << csv_text(p.u_reduced[i]) << ',' << csv_text(p.count[i]) << '\n';
    }
}

std::string method_text(const CompareSettings& settings) {
  std::ostringstream m;
  const auto& s = settings.run;
  m << "Each run directory is analysed as by `cdpost run` (doc/postproc.md): window = detected stationary regime "
       "(line fitted to U(t) drifting by at most "
    << short_number(s.criterion.max_relative_drift * 100) << "% over at least " << short_number(s.criterion.min_window_fraction * 100)
    << "% of the run) unless given; a run without one is analysed over its second half and marked *not stationary*. "
       "Spectra of v(t): Welch, Hann, segments of "
    << short_number(s.spectrum.segment_duration_s) << " s. f, A: highest peak above " << short_number(s.peak_fmin_hz)
    << " Hz; f_flow, A_flow: highest peak in [" << short_number(s.peak_fmin_hz) << ", " << short_number(settings.flow_band_max_hz)
    << "] Hz; f_contact_band, A_contact_band: highest peak in [" << short_number(settings.contact_band_low) << ", "
    << short_number(settings.contact_band_high)
    << "] x f_contact (capped at the Nyquist frequency): the spectrum smoothed over +-"
    << short_number(100 * settings.smoothing) << "% in frequency is compared with a power law fitted to it over the band "
       "(log-log); contact_excess is the largest ratio, and a peak (the highest bin of that feature) is reported when "
       "contact_excess >= "
    << short_number(settings.peak_excess) << ". A band maximum at an end of the flow band is no peak and is left out (\"-\"). f_contact = sqrt(2k/m)/(2 pi) with m the mass of a grain of diameter d "
       "and k the deck's stiffness (Hertz: the secant stiffness at the target overlap). Overlaps: every contact of every dump "
       "frame inside the window (grain pairs with the minimum image along x, grains and the floor), in d. Wall time per "
       "physical second: the last `Loop time` of the run's log (its flow stage; summed with those of the continuation "
       "runs in part2, part3, ... when the flow was run in parts) over the simulated time of those stages. "
       "cpu_per_physical_s: each loop's wall time times its process's CPU share, (user + sys)/wall from timing.txt (else "
       "LAMMPS's own CPU-use line): what the run would cost on a core of its own when other jobs shared the machine.";
  return m.str();
}

}  // namespace

void write_comparison(Comparison& comparison, const CompareSettings& settings, const std::string& out_dir) {
  const std::string figures_dir = out_dir + "/figures";
  fs::create_directories(figures_dir);
  write_table_csv(comparison, out_dir + "/table.csv");
  comparison.fits.write_csv(out_dir + "/fits.csv");
  write_long_csvs(comparison, out_dir);

  std::vector<const ComparedRun*> all;
  std::map<std::string, std::vector<const ComparedRun*>> by_code;
  for (const auto& r : comparison.runs) {
    all.push_back(&r);
    if (r.model != "rigid") by_code[r.code].push_back(&r);
  }
  std::vector<Figure> figures{spectra_figure(all, "spectra", "Spectra of v(t), every run (vertical lines: contact frequencies)")};
  for (auto& [code, runs] : by_code) {
    std::vector<const ComparedRun*> with_rigid;
    for (const auto& r : comparison.runs)
      if (r.model == "rigid") with_rigid.push_back(&r);
    with_rigid.insert(with_rigid.end(), runs.begin(), runs.end());
    std::string stem = code;
    std::replace(stem.begin(), stem.end(), '-', '_');
    figures.push_back(spectra_figure(with_rigid, "spectra_" + stem, "Spectra of v(t): rigid and " + code_name(code)));
  }
  figures.push_back(peaks_figure(comparison));
  figures.push_back(u_t_figure(comparison));
  figures.push_back(profiles_figure(comparison));
  auto bulk = bulk_figure(comparison);
  if (!bulk.panels.empty()) figures.push_back(bulk);
  figures.push_back(cost_figure(comparison));

  cdpost::MarkdownReport report("Rigid and soft-sphere runs of the chute, side by side");
  report.paragraph(method_text(settings));
  report.heading("Table");
  report.paragraph(markdown_table(comparison));
  report.heading("How the peaks move with k");
  report.table(comparison.fits);
  report.heading("Runs");
  std::ostringstream runs;
  for (const auto& r : comparison.runs) {
    runs << "- **" << r.label << "** (`" << r.directory << "`): window " << r.window_note;
    if (const auto* t0 = r.analysis.results.find("t_start"))
      runs << ", t = " << short_number(t0->value) << "–" << short_number(r.analysis.results.find("t_end")->value) << " sqrt(d/g)";
    if (auto dt = r.info.number("dt")) runs << "; dt = " << short_number(*dt) << " s";
    if (auto sample = r.info.number("sample_interval")) runs << "; sampling " << short_number(*sample) << " s";
    if (r.overlaps) runs << "; overlaps over " << r.overlaps->frames << " frames, " << r.overlaps->contacts << " contacts, p99 "
                         << short_number(r.overlaps->p99) << " d";
    if (r.loop_seconds) runs << "; flow loop " << short_number(*r.loop_seconds) << " s for " << short_number(*r.physical_seconds) << " s";
    runs << "\n";
  }
  report.paragraph(runs.str());
  report.heading("Figures");
  for (const auto& figure : figures) {
    if (auto problem = cdpost::render_figure(figure, figures_dir))
      comparison.warnings.push_back(*problem);
    else
      report.figure("figures", figure.name, figure.caption);
  }
  if (!settings.commands_file.empty()) {
    std::ifstream in(settings.commands_file);
    if (!in) throw cdpost::InputError(settings.commands_file, 0, "cannot read the commands file");
    std::stringstream text;
    text << in.rdbuf();
    report.heading("Commands");
    report.paragraph("```\n" + text.str() + "```");
  }
  report.warnings(comparison.warnings);
  report.write(out_dir + "/report.md");
}

}  // namespace cdref
