// cdref: the reference comparison of rigid and soft-sphere chute runs (doc/reference.md).
#include <filesystem>
#include <iostream>

#include "collision.h"
#include "comparison.h"
#include "io/line_source.h"
#include "io/options.h"
#include "overlaps.h"
#include "signal/statistics.h"
#include "spatial_to_chunk.h"

namespace {

using cdpost::OptionSpec;
using cdpost::ParsedOptions;
using cdpost::UsageError;

const char* const overview =
    "cdref: rigid and soft-sphere chute runs side by side (doc/reference.md)\n"
    "\n"
    "usage: cdref COMMAND [ARGUMENTS] [OPTIONS]     (cdref COMMAND --help for its options)\n"
    "\n"
    "commands:\n"
    "  compare DIR...              analyse run directories and write the comparison report\n"
    "  spatial-to-chunk IN OUT     convert LIGGGHTS fix ave/spatial output to fix ave/chunk format\n"
    "  overlaps DUMP               overlap statistics of the frames of a dump\n"
    "  collision FILE              restitution and contact steps of a recorded binary collision\n";

std::optional<ParsedOptions> parse(const std::string& command, const std::string& usage,
                                   const std::vector<std::string>& arguments, std::vector<OptionSpec> specs,
                                   size_t min_positional, size_t max_positional)
{
  specs.push_back({"help", "", "show this help"});
  auto options = cdpost::parse_options(command, arguments, specs);
  if (options.flag("help")) {
    std::cout << "usage: " << usage << "\n\noptions:\n" << cdpost::options_help(specs);
    return std::nullopt;
  }
  if (options.positional.size() < min_positional || options.positional.size() > max_positional)
    throw UsageError(command + ": usage: " + usage);
  return options;
}

int command_compare(const std::vector<std::string>& arguments)
{
  std::vector<OptionSpec> specs = {
      {"out", "DIR", "output directory (required)"},
      {"d", "METRES", "mean grain diameter when a run has no run.info (default 5e-4)"},
      {"g", "M/S2", "gravity (default 9.81)"},
      {"z0", "LENGTH", "wall-top height for runs without run.info (m; default 0)"},
      {"dt", "SECONDS", "time step for flow.time files without a time column"},
      {"t-start", "SECONDS", "start of the analysis window for every run (disables detection)"},
      {"t-end", "SECONDS", "end of the analysis window for every run"},
      {"max-drift", "FRACTION", "stationarity: largest drift of U across the window / mean (default 0.02)"},
      {"min-window", "FRACTION", "stationarity: smallest window, fraction of the run (default 0.25)"},
      {"segment", "SECONDS", "spectrum segment duration (default 0.25)"},
      {"overlap", "FRACTION", "spectrum segment overlap (default 0.5)"},
      {"fmin", "HZ", "lowest frequency of the peak searches (default 5)"},
      {"high-frequency", "HZ", "A_mean is the mean amplitude above this (default 100)"},
      {"flow-band", "HZ", "upper end of the flow band (default 500)"},
      {"contact-band", "LOW:HIGH", "contact band in multiples of f_contact (default 0.25:4)"},
      {"smoothing", "FRACTION", "contact band: smooth the spectrum over +-FRACTION x f (default 0.1)"},
      {"peak-excess", "RATIO", "a contact-band peak stands this far above the band's power law (default 1.5)"},
      {"dump-name", "FILE", "dump file in each run directory for the overlaps (default dump.chute)"},
      {"commands", "FILE", "text file with the commands that made the runs, quoted in the report"},
      {"progress", "", "name each run on stderr as it is analysed"}};
  auto options = parse("cdref compare", "cdref compare DIR... --out OUT [options]", arguments, specs, 1, 1000);
  if (!options) return 0;
  auto out = options->text("out");
  if (!out) throw UsageError("cdref compare: --out OUT is required");
  cdref::CompareSettings s;
  s.run_dirs = options->positional;
  auto& run = s.run;
  run.units.d_m = options->number("d").value_or(run.units.d_m);
  run.units.g_mps2 = options->number("g").value_or(run.units.g_mps2);
  run.z0 = options->number("z0").value_or(0);
  run.timestep_size = options->number("dt");
  run.t_start = options->number("t-start");
  run.t_end = options->number("t-end");
  run.criterion.max_relative_drift = options->number("max-drift").value_or(run.criterion.max_relative_drift);
  run.criterion.min_window_fraction = options->number("min-window").value_or(run.criterion.min_window_fraction);
  run.spectrum.segment_duration_s = options->number("segment").value_or(0.25);
  run.spectrum.overlap = options->number("overlap").value_or(run.spectrum.overlap);
  run.peak_fmin_hz = options->number("fmin").value_or(run.peak_fmin_hz);
  run.high_frequency_hz = options->number("high-frequency").value_or(run.high_frequency_hz);
  run.progress = options->flag("progress");
  s.flow_band_max_hz = options->number("flow-band").value_or(s.flow_band_max_hz);
  if (auto band = options->text("contact-band")) {
    auto colon = band->find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      s.contact_band_low = std::stod(band->substr(0, colon));
      s.contact_band_high = std::stod(band->substr(colon + 1));
    } catch (const std::exception&) {
      throw UsageError("cdref compare: --contact-band wants LOW:HIGH, e.g. 0.25:4, not '" + *band + "'");
    }
    if (!(s.contact_band_low > 0 && s.contact_band_high > s.contact_band_low))
      throw UsageError("cdref compare: --contact-band needs 0 < LOW < HIGH");
  }
  s.peak_excess = options->number("peak-excess").value_or(s.peak_excess);
  s.smoothing = options->number("smoothing").value_or(s.smoothing);
  if (!(s.smoothing >= 0 && s.smoothing < 1)) throw UsageError("cdref compare: --smoothing must be in [0, 1)");
  s.dump_name = options->text("dump-name").value_or(s.dump_name);
  s.commands_file = options->text("commands").value_or("");
  if (!(run.units.d_m > 0 && run.units.g_mps2 > 0)) throw UsageError("cdref compare: --d and --g must be positive");
  if (!(run.spectrum.segment_duration_s > 0)) throw UsageError("cdref compare: --segment must be positive");
  if (!(s.flow_band_max_hz > run.peak_fmin_hz)) throw UsageError("cdref compare: --flow-band must exceed --fmin");

  auto comparison = cdref::compare_runs(s);
  cdref::write_comparison(comparison, s, *out);
  for (const auto& w : comparison.warnings) std::cerr << "cdref: warning: " << w << '\n';
  std::cout << "table: " << *out << "/table.csv, report: " << *out << "/report.md\n";
  return 0;
}

int command_spatial_to_chunk(const std::vector<std::string>& arguments)
{
  auto options = parse("cdref spatial-to-chunk", "cdref spatial-to-chunk IN OUT", arguments, {}, 2, 2);
  if (!options) return 0;
  auto result = cdref::spatial_to_chunk(options->positional[0], options->positional[1]);
  std::cout << options->positional[1] << ": " << result.blocks << " blocks of " << result.bins << " chunks\n";
  return 0;
}

int command_overlaps(const std::vector<std::string>& arguments)
{
  auto options = parse("cdref overlaps", "cdref overlaps DUMP [options]", arguments,
                       {{"d", "LENGTH", "mean diameter in the dump's length unit (default 5e-4)"},
                        {"floor", "Y", "floor height (default: the bottom of the box)"},
                        {"first", "TIMESTEP", "skip frames before this timestep"},
                        {"last", "TIMESTEP", "skip frames after this timestep"}},
                       1, 1);
  if (!options) return 0;
  cdref::OverlapOptions o;
  o.mean_diameter = options->number("d").value_or(o.mean_diameter);
  o.floor_y = options->number("floor");
  o.first_timestep = options->integer("first").value_or(0);
  o.last_timestep = options->integer("last").value_or(-1);
  auto s = cdref::dump_overlaps(options->positional[0], o);
  std::cout << "frames " << s.frames << "\ncontacts " << s.contacts << "\nmean " << s.mean << "\nmean_of_max "
            << s.mean_of_max << "\np99 " << s.p99 << "\nmax " << s.max << "\n";
  return 0;
}

int command_collision(const std::vector<std::string>& arguments)
{
  auto options = parse("cdref collision", "cdref collision FILE", arguments, {}, 1, 1);
  if (!options) return 0;
  auto c = cdref::analyse_collision(options->positional[0]);
  std::cout << "restitution " << c.restitution << "\ncontact_steps " << c.contact_steps << "\napproach_speed "
            << c.approach_speed << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> arguments(argv + 1, argv + argc);
  try {
    if (arguments.empty() || arguments[0] == "--help" || arguments[0] == "help") {
      std::cout << overview;
      return arguments.empty() ? 2 : 0;
    }
    const std::string command = arguments[0];
    arguments.erase(arguments.begin());
    if (command == "compare") return command_compare(arguments);
    if (command == "spatial-to-chunk") return command_spatial_to_chunk(arguments);
    if (command == "overlaps") return command_overlaps(arguments);
    if (command == "collision") return command_collision(arguments);
    throw UsageError("unknown command '" + command + "'");
  } catch (const UsageError& e) {
    std::cerr << "cdref: error: " << e.what() << " (cdref --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cdref: error: " << e.what() << '\n';
    return 1;
  }
}
