#include "cli/commands.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>

#include "analysis/creep_results.h"
#include "analysis/fields.h"
#include "analysis/published_run.h"
#include "analysis/run_analysis.h"
#include "analysis/series_analysis.h"
#include "analysis/series_comparison.h"
#include "cli/run_parameters.h"
#include "figures/field_figures.h"
#include "figures/run_figures.h"
#include "figures/series_comparison_figures.h"
#include "figures/series_figures.h"
#include "figures/snapshot.h"
#include "io/ave_time.h"
#include "io/chute_record.h"
#include "io/line_source.h"
#include "io/options.h"

namespace cdpost {

namespace {

const char* const overview =
    "cdpost: analysis of Contact Dynamics chute runs (spectra, profiles, flow rules, figures, reports)\n"
    "\n"
    "usage: cdpost COMMAND [ARGUMENTS] [OPTIONS]     (cdpost COMMAND --help for its options)\n"
    "\n"
    "commands:\n"
    "  run DIR          analyse one run directory (flow.time, profile.chunk, layers.chunk, columns.chunk)\n"
    "  series MANIFEST  analyse the runs listed in a CSV (run,mu,theta[,L,stopped,h_stop]) and fit the flow rules\n"
    "  spectrum FILE    spectrum of one column of a fix ave/time file\n"
    "  snapshot DUMP    picture of one frame of a dump (grains coloured by x-velocity, walls)\n"
    "  creep PATH       the creep measure of a published profile.csv (or a published run folder holding one)\n"
    "  fields DUMP      coarse-grained packing, velocity, temperature and stress of a dump (map or profile)\n"
    "\n"
    "Results go to CSV and JSON beside the report; see doc/postproc.md.\n";

// Options naming the files of a run and their columns, bound to RunColumns members.
struct ColumnOption {
  const char* name;
  std::string RunColumns::*member;
  const char* help;
};
const std::vector<ColumnOption> column_options = {
    {"time-file", &RunColumns::time_file, "fix ave/time file of the run"},
    {"col-timestep", &RunColumns::timestep, "its timestep column"},
    {"col-time", &RunColumns::time, "its time column (optional; else TimeStep * --dt)"},
    {"col-u-all", &RunColumns::u_all, "mean x-velocity of all grains (optional)"},
    {"col-u-flow", &RunColumns::u_flow, "mean x-velocity of the grains with z > 0"},
    {"col-v-flow", &RunColumns::v_flow, "mean z-velocity of the grains with z > 0"},
    {"col-phi", &RunColumns::phi, "area fraction of the flowing layer (optional)"},
    {"col-h", &RunColumns::h, "flowing-layer thickness (optional; else from the profile)"},
    {"profile-file", &RunColumns::profile_file, "fix ave/chunk file of the velocity profile"},
    {"col-profile-z", &RunColumns::profile_coord, "its bin-centre column"},
    {"col-profile-vx", &RunColumns::profile_vx, "its x-velocity column"},
    {"col-profile-count", &RunColumns::profile_count, "its grain-count column"},
    {"layers-file", &RunColumns::layers_file, "fix ave/chunk file of v per layer"},
    {"col-layers-z", &RunColumns::layers_coord, "its layer-centre column"},
    {"col-layers-v", &RunColumns::layers_vz, "its normal-velocity column"},
    {"col-layers-count", &RunColumns::layers_count, "its grain-count column (optional)"},
    {"columns-file", &RunColumns::columns_file, "fix ave/chunk file of the layer's v per x-column"},
    {"col-columns-v", &RunColumns::columns_v, "its normal-velocity column"},
};

std::vector<OptionSpec> unit_options()
{
  return {{"d", "METRES", "mean grain diameter (default: the run's chute.params, else 5e-4)"},
          {"g", "M/S2", "gravity (default: the run's chute.params, else 9.81)"},
          {"units", "si|reduced", "units of the input: SI (default) or reduced (d, sqrt(d/g))"},
          {"length-unit", "METRES", "one input length unit in metres (overrides --units)"},
          {"time-unit", "SECONDS", "one input time unit in seconds (overrides --units)"},
          {"dt", "TIME", "time-step size in input time units (time = TimeStep * dt)"},
          {"progress", "", "show progress on stderr even when it is not a terminal"},
          {"help", "", "show this help"}};
}

std::vector<OptionSpec> creep_options()
{
  return {{"creep-depth", "D", "the creep measure reads the bins with -D <= z < 0, in d (default 30)"},
          {"creep-floor", "U",
           "noise floor of u in the bed, in sqrt(g d): the creep fit range ends where u first falls below 10 U "
           "(default: estimated from the profile, doc/postproc.md)"}};
}

// A number option that must be positive when given.
std::optional<double> positive_option(const ParsedOptions& options, const std::string& name, const std::string& command)
{
  auto value = options.number(name);
  if (value && !(*value > 0)) throw UsageError(command + ": --" + name + " must be positive");
  return value;
}

CreepSettings creep_settings_from(const ParsedOptions& options, const std::string& command)
{
  CreepSettings creep;
  creep.depth_d = positive_option(options, "creep-depth", command).value_or(creep.depth_d);
  creep.floor_reduced = positive_option(options, "creep-floor", command);
  return creep;
}

std::vector<OptionSpec> analysis_options()
{
  std::vector<OptionSpec> specs = unit_options();
  std::vector<OptionSpec> more = {
      {"t-start", "TIME", "start of the stationary window (input time units; disables detection)"},
      {"t-end", "TIME", "end of the stationary window (input time units)"},
      {"max-drift", "FRACTION", "stationarity: largest drift of U across the window / mean (default 0.02)"},
      {"min-window-fraction", "FRACTION", "stationarity: smallest window, fraction of the run (default 0.25)"},
      {"segment", "SECONDS", "spectrum segment duration (default 1)"},
      {"overlap", "FRACTION", "spectrum segment overlap (default 0.5)"},
      {"fmin", "HZ", "lowest frequency searched for the peak (default 5)"},
      {"fmax", "HZ", "highest frequency searched for the peak (default Nyquist)"},
      {"high-frequency", "HZ", "A_mean is the mean amplitude above this (default 100)"},
      {"sample-rate", "HZ",
       "spectra use the samples on this rate's grid (default: the run's chute.params, else the time file's "
       "longest interval)"},
      {"z0", "LENGTH",
       "height of the wall tops in input length units, z = y - z0 (default: the run's chute.params; "
       "needed without one)"},
      {"cell-length", "D", "cell length L in d, the deck's L: needed for the columns of columns.chunk"},
      {"blocks", "N", "blocks for the standard error of means (default 10)"},
      {"out", "DIR", "output directory"}};
  specs.insert(specs.end(), more.begin(), more.end());
  const auto creep = creep_options();
  specs.insert(specs.end(), creep.begin(), creep.end());
  for (const auto& c : column_options)
    specs.push_back({c.name, "NAME", std::string(c.help) + " (default " + RunColumns().*c.member + ")"});
  return specs;
}

RunSettings settings_from(const ParsedOptions& options, const std::string& command)
{
  RunSettings s;
  s.units = units_from(options, command);
  s.timestep_size = options.number("dt");
  s.t_start = options.number("t-start");
  s.t_end = options.number("t-end");
  s.criterion.max_relative_drift = options.number("max-drift").value_or(s.criterion.max_relative_drift);
  s.criterion.min_window_fraction = options.number("min-window-fraction").value_or(s.criterion.min_window_fraction);
  s.spectrum.segment_duration_s = options.number("segment").value_or(s.spectrum.segment_duration_s);
  s.spectrum.overlap = options.number("overlap").value_or(s.spectrum.overlap);
  s.peak_fmin_hz = options.number("fmin").value_or(s.peak_fmin_hz);
  s.peak_fmax_hz = options.number("fmax").value_or(s.peak_fmax_hz);
  s.high_frequency_hz = options.number("high-frequency").value_or(s.high_frequency_hz);
  s.sample_rate_hz = positive_option(options, "sample-rate", command);
  s.z0 = options.number("z0").value_or(s.z0);  // else a run folder's record (run_parameters.h)
  s.creep = creep_settings_from(options, command);
  s.cell_length_d = positive_option(options, "cell-length", command);
  s.averaging_blocks = static_cast<int>(options.integer("blocks").value_or(s.averaging_blocks));
  s.progress = options.flag("progress");
  for (const auto& c : column_options)
    if (auto name = options.text(c.name)) s.columns.*c.member = *name;
  if (s.averaging_blocks < 2) throw UsageError(command + ": --blocks must be at least 2");
  if (!(s.spectrum.segment_duration_s > 0)) throw UsageError(command + ": --segment must be positive");
  if (s.t_start && s.t_end && !(*s.t_end > *s.t_start))
    throw UsageError(command + ": --t-end " + *options.text("t-end") + " is not after --t-start " +
                     *options.text("t-start") + ": the window ends before it starts");
  return s;
}

// Parses `arguments`, printing help and returning nothing if --help was asked.
std::optional<ParsedOptions> parse_or_help(const std::string& command, const std::string& usage,
                                           const std::vector<std::string>& arguments,
                                           const std::vector<OptionSpec>& specs, size_t positional_count)
{
  auto options = parse_options(command, arguments, specs);
  if (options.flag("help")) {
    std::cout << "usage: " << usage << "\n\noptions:\n" << options_help(specs);
    return std::nullopt;
  }
  if (options.positional.size() != positional_count) throw UsageError(command + ": usage: " + usage);
  return options;
}

// The folder holding `file`, "." for a bare name: where its run's chute.params would be.
std::string folder_of(const std::string& file)
{
  const auto folder = std::filesystem::path(file).parent_path();
  return folder.empty() ? "." : folder.string();
}

void print_warnings(const std::vector<std::string>& warnings)
{
  for (const auto& w : warnings) std::cerr << "cdpost: warning: " << w << '\n';
}

const OptionSpec obstacle_types_option = {
    "obstacle-types", "T1,T2,...",
    "atom types that are obstacles, not grains (e.g. a ring moved by fix move): drawn in grey, off the colour "
    "scale (the dump's type column; default: none)"};

// --obstacle-types: positive atom types separated by commas; empty when not given.
std::vector<long> obstacle_types(const ParsedOptions& options, const std::string& command)
{
  std::vector<long> types;
  const auto given = options.text("obstacle-types");
  if (!given) return types;
  const auto refuse = [&] {
    return UsageError(command + ": --obstacle-types takes positive atom types separated by commas (e.g. 2,3), not '" +
                      *given + "'");
  };
  size_t start = 0;
  while (start <= given->size()) {
    const size_t comma = std::min(given->find(',', start), given->size());
    const std::string item = given->substr(start, comma - start);
    if (item.empty() || item.find_first_not_of("0123456789") != std::string::npos || item.size() > 9) throw refuse();
    types.push_back(std::stol(item));
    if (types.back() < 1) throw refuse();
    start = comma + 1;
  }
  return types;
}

int command_run(const std::vector<std::string>& arguments)
{
  auto specs = analysis_options();
  specs.push_back({"dump", "FILE", "LAMMPS dump (.gz allowed) for the snapshot figure; default: none"});
  specs.push_back(obstacle_types_option);
  auto options = parse_or_help("cdpost run", "cdpost run DIR [options]", arguments, specs, 1);
  if (!options) return 0;
  auto settings = settings_from(*options, "cdpost run");
  const auto obstacles = obstacle_types(*options, "cdpost run");
  if (!obstacles.empty() && !options->text("dump"))
    throw UsageError("cdpost run: --obstacle-types is for the snapshot: give --dump too");
  settings.directory = options->positional[0];
  if (!std::filesystem::is_directory(settings.directory)) throw InputError(settings.directory, 0, "not a directory");
  apply_run_parameters(settings, *options, "cdpost run");
  std::cout << "parameters: " << settings.parameters << '\n';
  auto out = options->text("out").value_or((std::filesystem::path(settings.directory) / "post").string());
  auto run = analyse_run(settings);
  write_run_outputs(run, out, options->text("dump").value_or(""), obstacles);
  std::cout << run.results.text() << "results: " << out << "/results.csv, report: " << out << "/report.md\n";
  print_warnings(run.warnings);
  return 0;
}

// The parameters line of each run of a series that has one, led by `prefix`.
void print_run_parameters(const SeriesAnalysis& series, const std::string& prefix)
{
  for (const auto& run : series.runs)
    if (!run.analysis.settings.parameters.empty())
      std::cout << prefix << run.entry.name << ": parameters: " << run.analysis.settings.parameters << '\n';
}

// The names of the two series of --compare: --labels A,B, else default_labels.
std::array<std::string, 2> comparison_labels(const ParsedOptions& options, const std::string& other)
{
  const auto given = options.text("labels");
  const auto comma = given ? given->find(',') : std::string::npos;
  if (given && (comma == std::string::npos || given->find(',', comma + 1) != std::string::npos))
    throw UsageError("cdpost series: --labels takes two names separated by one comma, not '" + *given + "'");
  auto labels = given ? std::array<std::string, 2>{given->substr(0, comma), given->substr(comma + 1)}
                      : default_labels(options.positional[0], other);
  for (const auto& label : labels)
    if (label.empty() || label.find_first_of(",\"\n") != std::string::npos)
      throw UsageError("cdpost series: a series label must be a non-empty name without commas or quotes, not '" +
                       label + "' (--labels A,B)");
  if (labels[0] == labels[1])
    throw UsageError("cdpost series: both series are labelled '" + labels[0] + "': give --labels A,B");
  return labels;
}

int command_compare(const ParsedOptions& options, const SeriesSettings& series, const std::string& other)
{
  const auto labels = comparison_labels(options, other);
  auto out =
      options.text("out").value_or((std::filesystem::path(series.manifest).parent_path() / "series-compare").string());
  auto comparison = compare_series(series, other, labels);
  for (size_t s = 0; s < 2; ++s) print_run_parameters(comparison.series[s], labels[s] + ": ");
  write_comparison_outputs(comparison, out);
  std::cout << "compared " << labels[0] << " and " << labels[1] << ": " << out << "/compared_fits.csv, report: " << out
            << "/report.md\n";
  print_warnings(comparison_warnings(comparison));
  return 0;
}

int command_series(const std::vector<std::string>& arguments)
{
  auto specs = analysis_options();
  specs.insert(specs.end(),
               {{"compare", "MANIFEST", "analyse this series too, as alone, and compare both"},
                {"labels", "A,B", "names of the series with --compare (default: the manifests' folders)"},
                {"source", "FILE", "the numbers of a source study to compare with (e.g. results/source.csv)"}});
  auto options =
      parse_or_help("cdpost series", "cdpost series MANIFEST.csv [--compare OTHER.csv] [options]", arguments, specs, 1);
  if (!options) return 0;
  SeriesSettings series;
  series.run = settings_from(*options, "cdpost series");
  series.manifest = options->positional[0];
  series.source_file = options->text("source").value_or("");
  series.complete_run = [&](RunSettings& run) { apply_run_parameters(run, *options, "cdpost series"); };
  if (auto other = options->text("compare")) return command_compare(*options, series, *other);
  if (options->text("labels")) throw UsageError("cdpost series: --labels names the series of --compare");
  auto out =
      options->text("out").value_or((std::filesystem::path(series.manifest).parent_path() / "series-post").string());
  auto result = analyse_series(series);
  print_run_parameters(result, "");
  write_series_outputs(result, out);
  std::cout << result.fits.text() << "results: " << out << "/fits.csv, " << out << "/runs.csv, " << out
            << "/residuals.csv, " << out << "/depth_decay.csv, report: " << out << "/report.md\n";
  print_warnings(result.warnings);
  return 0;
}

int command_spectrum(const std::vector<std::string>& arguments)
{
  auto specs = analysis_options();
  specs.push_back({"column", "NAME", "column to transform (default v_v_flow)"});
  auto options =
      parse_or_help("cdpost spectrum", "cdpost spectrum FILE [--column NAME] [options]", arguments, specs, 1);
  if (!options) return 0;
  auto settings = settings_from(*options, "cdpost spectrum");
  const auto recorded =
      run_parameters(*options, "cdpost spectrum", folder_of(options->positional[0]), WallTops::optional);
  settings.units = recorded.units;
  settings.sample_rate_hz = recorded.sample_rate_hz;
  if (recorded.recorded) std::cout << "parameters: " << recorded.description << '\n';
  const std::string column = options->text("column").value_or(settings.columns.v_flow);
  auto run = analyse_column_spectrum(options->positional[0], column, settings);
  std::cout << run.results.text();
  if (auto out = options->text("out")) {
    std::filesystem::create_directories(*out);
    run.results.write_csv(*out + "/spectrum_results.csv");
    write_columns_csv(*out + "/spectrum.csv", {"f_Hz", "A"}, {run.spectrum.frequency_hz, run.spectrum.amplitude});
  }
  return 0;
}

// --periodic: "x", "y", "xy" or "none"; nothing when not given.
std::optional<std::array<bool, 2>> periodic_option(const ParsedOptions& options, const std::string& command)
{
  const auto given = options.text("periodic");
  if (!given) return std::nullopt;
  const std::map<std::string, std::array<bool, 2>> axes = {
      {"x", {true, false}}, {"y", {false, true}}, {"xy", {true, true}}, {"none", {false, false}}};
  const auto found = axes.find(*given);
  if (found == axes.end()) throw UsageError(command + ": --periodic takes x, y, xy or none, not '" + *given + "'");
  return found->second;
}

int command_snapshot(const std::vector<std::string>& arguments)
{
  auto specs = unit_options();
  for (auto& spec : specs) {
    if (spec.name == "d")
      spec.help =
          "mean grain diameter (default: the chute.params beside the dump, else the dump's mean diameter, "
          "from its radius column)";
    if (spec.name == "g")
      spec.help =
          "gravity in the dump's units, which the colours u_x / sqrt(g d) are scaled by (default: the chute.params "
          "beside the dump; without one, needed unless --units reduced)";
  }
  specs.insert(specs.end(), {{"timestep", "N", "frame to draw (default: the last)"},
                             {"z0", "LENGTH",
                              "height of the wall tops in input length units: walls on the periodic boundary from the "
                              "box bottom up to it, periodic images shaded above it (default: the chute.params beside "
                              "the dump, else no walls)"},
                             {"periodic", "x|y|xy|none",
                              "the periodic dimensions, whose images are shaded (default: the dump's "
                              "'ITEM: BOX BOUNDS' flags)"},
                             obstacle_types_option,
                             {"out", "DIR", "output directory (default: the dump's directory)"}});
  auto options = parse_or_help("cdpost snapshot", "cdpost snapshot DUMP [options]", arguments, specs, 1);
  if (!options) return 0;
  SnapshotRequest request;
  request.dump_path = options->positional[0];
  request.timestep = options->integer("timestep");
  request.progress = options->flag("progress");
  request.periodic = periodic_option(*options, "cdpost snapshot");
  request.obstacle_types = obstacle_types(*options, "cdpost snapshot");
  auto out = options->text("out").value_or(std::filesystem::path(request.dump_path).parent_path().string());
  if (out.empty()) out = ".";
  const auto recorded = run_parameters(*options, "cdpost snapshot", folder_of(request.dump_path), WallTops::optional);
  if (recorded.recorded) std::cout << "parameters: " << recorded.description << '\n';
  request.diameter_from_dump = !recorded.d_given;
  request.wall_tops = recorded.z0;
  auto snapshot = snapshot_figure(request, recorded.units);
  // The colours are u_x / sqrt(g d): a dump that no chute.params describes (a deck in other units)
  // gives no g, and 9.81 m/s^2 would colour an LJ run several times off. Asked after reading the
  // dump, so that a dump cdpost cannot read is named first.
  if (!recorded.recorded && !options->text("g") && options->text("units").value_or("si") != "reduced")
    throw InputError(request.dump_path, 0,
                     "no chute.params beside it to take g and the units from: give --g, gravity in the dump's "
                     "units (the colours are u_x / sqrt(g d)), or --units reduced");
  std::cout << "snapshot: " << snapshot.parameters << '\n';
  std::filesystem::create_directories(out);
  if (auto problem = render_figure(snapshot.figure, out)) throw std::runtime_error(*problem);
  std::cout << "snapshot: " << out << "/snapshot.png, " << out << "/snapshot.svg\n";
  return 0;
}

int command_creep(const std::vector<std::string>& arguments)
{
  auto specs = creep_options();
  specs.push_back(
      {"update", "", "PATH is a published run folder: replace the creep_* rows of its results.csv and results.json"});
  specs.push_back({"help", "", "show this help"});
  auto options = parse_or_help("cdpost creep", "cdpost creep PROFILE.csv|RUN_FOLDER [options]", arguments, specs, 1);
  if (!options) return 0;
  const auto settings = creep_settings_from(*options, "cdpost creep");
  const std::filesystem::path path = options->positional[0];
  const bool folder = std::filesystem::is_directory(path);
  if (options->flag("update") && !is_published_run(path.string()))
    throw UsageError("cdpost creep: --update needs a published run folder (holding results.csv), not " + path.string());
  const auto profile_path = folder ? (path / "profile.csv").string() : path.string();
  const auto profile = read_published_profile(profile_path);
  const auto creep = measure_creep(profile.z_d, profile.u, settings);
  ResultTable results;
  add_creep_results(results, creep);
  std::cout << results.text();
  std::vector<std::string> warnings;
  for (const auto& problem : creep_problems(creep)) warnings.push_back(profile_path + ": creep " + problem);
  if (options->flag("update")) {
    update_published_creep(path.string(), creep);
    std::cout << "updated: " << (path / "results.csv").string() << ", " << (path / "results.json").string() << '\n';
  }
  print_warnings(warnings);
  return 0;
}

// "A:B" as two numbers, A below B.
std::array<double, 2> interval_option(const ParsedOptions& options, const std::string& name)
{
  const auto text = *options.text(name);
  const auto colon = text.find(':');
  try {
    if (colon != std::string::npos) {
      size_t used_low = 0, used_high = 0;
      const double low = std::stod(text.substr(0, colon), &used_low);
      const double high = std::stod(text.substr(colon + 1), &used_high);
      if (used_low == colon && used_high == text.size() - colon - 1 && std::isfinite(low) && std::isfinite(high) &&
          high > low)
        return {low, high};
    }
  } catch (const std::exception&) {
  }
  throw UsageError("cdpost fields: --" + name + " takes LOW:HIGH with LOW below HIGH, not '" + text + "'");
}

// --cells N or NX,NY.
std::array<size_t, 2> cells_option(const ParsedOptions& options, bool profile)
{
  const auto text = options.text("cells");
  if (!text) return {0, 0};
  const auto comma = text->find(',');
  auto count = [&](const std::string& part) {
    size_t used = 0;
    long value = 0;
    try {
      value = std::stol(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != part.size() || value < 1 || value > 100000)
      throw UsageError("cdpost fields: --cells takes N (a profile) or NX,NY (a map), whole numbers from 1, not '" +
                       *text + "'");
    return static_cast<size_t>(value);
  };
  if (profile != (comma == std::string::npos))
    throw UsageError(std::string("cdpost fields: --cells takes ") + (profile ? "N for a profile" : "NX,NY for a map") +
                     ", not '" + *text + "'");
  if (profile) return {count(*text), 0};
  return {count(text->substr(0, comma)), count(text->substr(comma + 1))};
}

int command_fields(const std::vector<std::string>& arguments)
{
  const std::string command = "cdpost fields";
  const std::vector<OptionSpec> specs = {
      {"contacts", "FILE",
       "dump local of the fix's local array (f_ID[1] ... f_ID[7]): the contact stress; default none"},
      {"kernel", "gauss|lucy", "coarse-graining kernel: Gaussian cut at 3 widths (default) or Lucy's polynomial"},
      {"width", "LENGTH", "kernel width, its standard deviation along an axis (default d / 2)"},
      {"along", "x|y", "a profile along this axis, averaged over the other (default: a map)"},
      {"polar", "CX,CY,RIN,ROUT",
       "polar cells about (CX, CY) between radii RIN and ROUT, e.g. a drum (default: a map); --cells NR,NTHETA"},
      {"cells", "N|NX,NY",
       "nodes of the profile or the map (default: spacing width / 2 for a profile, width for a map)"},
      {"range", "LOW:HIGH", "extent of the profile, or the map's y extent (default: the first frame's box)"},
      {"x-range", "LOW:HIGH", "the map's x extent (default: the first frame's box)"},
      {"periodic", "x|y|xy|none", "the periodic dimensions (default: the dump's 'ITEM: BOX BOUNDS' flags)"},
      {"t-start", "TIME", "first frame averaged (time from 'ITEM: TIME', else timestep x --dt)"},
      {"t-end", "TIME", "last frame averaged"},
      {"dt", "TIME", "time step of the run: forces are impulse / dt (default: chute.params beside the dump)"},
      {"density", "RHO", "grain density when the dump has no mass column: masses pi r^2 rho (default: chute.params)"},
      {"d", "LENGTH", "grain diameter of I (default: chute.params, else the first frame's mean diameter)"},
      {"units", "si|lj", "units of the dump (default: SI when a chute.params is beside it; needed otherwise)"},
      {"image-velocity", "V",
       "a sheared periodic box (fix deform xy, remap v): x-velocity of the image across y, the tilt's rate "
       "(with --along y; default 0)"},
      {"theta", "THETA",
       "the fix's Moreau-Jean theta: contacts' branch vectors at x - theta dt v, where the fix solved them (default "
       "0.5, the fix's)"},
      {"dense-phi", "PHI", "mu(I) and phi(I) show the nodes at least this dense (default 0.5)"},
      {"out", "DIR", "output directory (default: DIR_OF_DUMP/fields)"},
      {"progress", "", "show progress on stderr even when it is not a terminal"},
      {"help", "", "show this help"}};
  auto options = parse_or_help(command, "cdpost fields DUMP [--contacts LOCAL_DUMP] [options]", arguments, specs, 1);
  if (!options) return 0;
  FieldsSettings s;
  s.dump_path = options->positional[0];
  s.contacts_path = options->text("contacts").value_or("");
  const auto folder = folder_of(s.dump_path);
  const auto record = read_chute_record(folder);
  const auto units = options->text("units");
  if (units && *units == "si") s.units = FieldUnits::si("from --units");
  else if (units && *units == "lj") s.units = FieldUnits::lj("from --units");
  else if (units) throw UsageError(command + ": --units takes si or lj, not '" + *units + "'");
  else if (record) s.units = FieldUnits::si("from " + record->source);
  else
    throw UsageError(command + ": no chute.params beside " + s.dump_path +
                     " to take the units from: give --units si or --units lj");
  const bool record_applies = record && s.units.system == "si";
  auto recorded = [&](const std::string& name) {
    return record_applies ? record->find(name) : std::optional<double>();
  };
  const auto kernel = options->text("kernel").value_or("gauss");
  if (kernel == "gauss") s.kernel = KernelShape::gaussian;
  else if (kernel == "lucy") s.kernel = KernelShape::lucy;
  else throw UsageError(command + ": --kernel takes gauss or lucy, not '" + kernel + "'");
  const auto along = options->text("along");
  if (along && *along != "x" && *along != "y")
    throw UsageError(command + ": --along takes x or y, not '" + *along + "'");
  s.along = along ? (*along == "x" ? 0 : 1) : -1;
  s.cells = cells_option(*options, along.has_value());
  if (auto polar = options->text("polar")) {
    if (along) throw UsageError(command + ": --polar and --along are two geometries: give one");
    std::vector<double> numbers;
    std::stringstream parts(*polar);
    for (std::string part; std::getline(parts, part, ',');) {
      size_t used = 0;
      double value = std::nan("");
      try {
        value = std::stod(part, &used);
      } catch (const std::exception&) {
      }
      if (used != part.size() || !std::isfinite(value)) numbers.clear(), parts.setstate(std::ios::failbit);
      else numbers.push_back(value);
    }
    if (numbers.size() != 4 || !(numbers[2] >= 0 && numbers[3] > numbers[2]))
      throw UsageError(command + ": --polar takes CX,CY,RIN,ROUT with 0 <= RIN < ROUT, not '" + *polar + "'");
    s.polar = PolarCells{numbers[0], numbers[1], numbers[2], numbers[3], s.cells[0], s.cells[1]};
  }
  if (options->text("range")) s.range = interval_option(*options, "range");
  if (options->text("x-range")) {
    if (along) throw UsageError(command + ": --x-range is a map's; a profile takes --range");
    s.x_range = interval_option(*options, "x-range");
  }
  s.periodic = periodic_option(*options, command);
  s.t_start = options->number("t-start");
  s.t_end = options->number("t-end");
  if (s.t_start && s.t_end && !(*s.t_end > *s.t_start))
    throw UsageError(command + ": --t-end is not after --t-start: the window ends before it starts");
  s.timestep_size = positive_option(*options, "dt", command);
  const bool dt_recorded = !s.timestep_size && recorded("dt_s");
  if (dt_recorded) s.timestep_size = recorded("dt_s");
  s.grain_density = positive_option(*options, "density", command);
  if (!s.grain_density) s.grain_density = recorded("density_kgpm3");
  s.diameter = positive_option(*options, "d", command);
  if (!s.diameter) s.diameter = recorded("d_m");
  s.image_velocity = options->number("image-velocity");
  if (s.image_velocity && s.along != 1) throw UsageError(command + ": --image-velocity needs --along y");
  s.theta = options->number("theta").value_or(s.theta);
  if (!(s.theta >= 0.5 && s.theta <= 1))
    throw UsageError(command + ": --theta " + std::to_string(s.theta) + ": the fix's theta lies in [0.5, 1]");
  s.dense_phi = options->number("dense-phi").value_or(s.dense_phi);
  s.progress = options->flag("progress");
  const auto width = positive_option(*options, "width", command);
  if (width) s.width = *width;
  else if (s.diameter) s.width = 0.5 * *s.diameter;
  else throw UsageError(command + ": give --width (or --d, whose half is the default width)");
  if (s.polar && !s.polar->rings) {  // cells about a width wide
    s.polar->rings = static_cast<size_t>(std::ceil((s.polar->r_out - s.polar->r_in) / s.width));
    s.polar->sectors = static_cast<size_t>(std::ceil(M_PI * (s.polar->r_in + s.polar->r_out) / s.width));
  }
  const auto out = options->text("out").value_or((std::filesystem::path(folder) / "fields").string());

  const auto fields = compute_fields(s);
  write_fields_tables(fields, out);
  std::cout << "fields: units " << s.units.describe() << "\nfields: " << fields.kernel_description << "; "
            << fields.frames << " frames, timesteps " << fields.first_step << " to " << fields.last_step
            << (s.contacts_path.empty() ? "; no contact dump: kinetic stress only"
                                        : "; " + std::to_string(std::lround(fields.mean_contacts)) +
                                              " contacts a frame from " + s.contacts_path)
            << "\n";
  std::vector<std::string> warnings = fields.warnings;
  if (dt_recorded && !s.contacts_path.empty())
    warnings.push_back("forces are impulse / dt_s of " + record->source +
                       ": a run whose step follows the flow (adapt_dt) needs --dt, its step at the dumped frames");
  for (const auto& figure : field_figures(fields))
    if (auto problem = render_figure(figure, out)) warnings.push_back(*problem);
  std::cout << "fields: " << out << "/fields.csv, " << out << "/fields.json, figures " << out << "/fields_*.png\n";
  print_warnings(warnings);
  return 0;
}

}  // namespace

int run_command_line(const std::vector<std::string>& arguments)
{
  const std::map<std::string, std::function<int(const std::vector<std::string>&)>> commands = {
      {"run", command_run},           {"series", command_series}, {"spectrum", command_spectrum},
      {"snapshot", command_snapshot}, {"creep", command_creep},   {"fields", command_fields}};
  if (arguments.empty() || arguments[0] == "--help" || arguments[0] == "-h" || arguments[0] == "help") {
    std::cout << overview;
    return arguments.empty() ? 2 : 0;
  }
  try {
    auto command = commands.find(arguments[0]);
    if (command == commands.end()) throw UsageError("unknown command '" + arguments[0] + "'");
    return command->second({arguments.begin() + 1, arguments.end()});
  } catch (const UsageError& e) {
    std::cerr << "cdpost: " << e.what() << " (see cdpost --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cdpost: error: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace cdpost
