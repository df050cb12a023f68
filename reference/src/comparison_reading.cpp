// What cdref reads of a run folder besides cdpost's analysis: samples, cost, overlaps.
#include "comparison_reading.h"

#include <algorithm>
#include <filesystem>

#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/tokens.h"

namespace cdref {

namespace fs = std::filesystem;

Samples read_samples(const cdpost::RunSettings& s)
{
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

namespace {

std::optional<std::string> find_log(const std::string& dir)
{
  for (const char* name : {"log.lammps", "log.liggghts", "log.cd"})
    if (fs::exists(fs::path(dir) / name)) return (fs::path(dir) / name).string();
  return std::nullopt;
}

// (user + sys)/wall of a process from run_comparison.sh's timing.txt ("wall user sys").
std::optional<double> process_share(const fs::path& dir)
{
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

}  // namespace

void read_cost(ComparedRun& run, const Samples& samples, double time_unit_s, std::vector<std::string>& warnings)
{
  if (samples.timestep.size() < 2) return;
  const double seconds_per_step =
      (samples.time.back() - samples.time.front()) / (samples.timestep.back() - samples.timestep.front()) * time_unit_s;
  double wall = 0, cpu = 0, physical = 0;
  bool cpu_known = true;
  for (int part = 1;; ++part) {
    const fs::path dir =
        part == 1 ? fs::path(run.directory) : fs::path(run.directory) / ("part" + std::to_string(part));
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
    if (share) cpu += flow.seconds * *share;
    else cpu_known = false;
    if (part == 1) run.cpu_percent = flow.cpu_percent;
  }
  run.loop_seconds = wall;
  run.physical_seconds = physical;
  if (cpu_known && wall > 0) run.process_cpu_share = cpu / wall;
}

void read_overlaps(ComparedRun& run, const CompareSettings& settings, const cdpost::RunSettings& s,
                   const Samples& samples, std::vector<std::string>& warnings)
{
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

}  // namespace cdref
