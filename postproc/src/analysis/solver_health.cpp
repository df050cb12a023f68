#include "analysis/solver_health.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/line_source.h"
#include "signal/statistics.h"

namespace cdpost {

namespace {

// The name of the column f_ID[K] of the fix's output K, whatever the ID; none if absent.
const std::string* fix_output_name(const ColumnTable& table, int output)
{
  const std::string suffix = "[" + std::to_string(output) + "]";
  for (const auto& name : table.names)
    if (name.rfind("f_", 0) == 0 && name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return &name;
  return nullptr;
}

// The column f_ID[K] of the fix's output K, whatever the ID.
const std::vector<double>& fix_output(const ColumnTable& table, int output)
{
  if (const std::string* name = fix_output_name(table, output)) return table.column(*name);
  const std::string suffix = "[" + std::to_string(output) + "]";
  throw InputError(table.source, 0,
                   "no column f_ID" + suffix + " (fix contact/dynamics output " + std::to_string(output) + ") among " +
                       join_names(table.names));
}

// Nearest-rank quantile of `values` (not empty).
double quantile(std::vector<double> values, double q)
{
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<size_t>(std::ceil(q * double(values.size())));
  return values[std::clamp<size_t>(rank, 1, values.size()) - 1];
}

std::string number(double value)
{
  return format_estimate(value, std::nullopt);
}

constexpr const char* kSolverFile = "solver.time";
constexpr const char* kLogFile = "log.lammps";
constexpr const char* kLogTag = "Fix contact/dynamics ";
constexpr const char* kLogSolver = " solver: ";
constexpr const char* kExtremesTag = "SOLVER ";

// The numbers of a solver line's text after "solver: " ("N steps, U unconverged (F %), largest
// final norm R, sweeps per step median M, 99th percentile P, max X, ..."): N, U, M, P, X.
std::optional<std::array<double, 5>> solver_line_numbers(const std::string& summary)
{
  std::array<double, 5> n{};
  if (std::sscanf(summary.c_str(),
                  "%lf steps, %lf unconverged (%*[^)]), largest final norm %*[^,], sweeps per step median %lf, "
                  "99th percentile %lf, max %lf",
                  &n[0], &n[1], &n[2], &n[3], &n[4]) != 5)
    return std::nullopt;
  return n;
}

}  // namespace

std::string count_text(double count)
{
  return std::to_string(std::llround(count));
}

SolverHealth solver_health(const ColumnTable& table)
{
  if (table.rows() == 0) throw InputError(table.source, 0, "no rows: the run wrote no solver_interval");
  const auto& timestep = table.column("TimeStep");
  const auto& sweeps = fix_output(table, 1);
  const auto& overlap = fix_output(table, 5);
  const auto& converged = fix_output(table, 7);
  SolverHealth health;
  health.source = table.source;
  health.rows = table.rows();
  for (size_t row = 0; row < table.rows(); ++row) {
    if (!(converged[row] >= 0 && converged[row] <= 1))
      throw InputError(table.source, table.row_lines[row],
                       "fraction of converged steps " + number(converged[row]) + " is not in [0, 1]");
    if (row > 0 && !(timestep[row] > timestep[row - 1]))
      throw InputError(table.source, table.row_lines[row], "TimeStep does not increase");
    const double steps = row > 0            ? timestep[row] - timestep[row - 1]
                         : table.rows() > 1 ? timestep[1] - timestep[0]
                         : timestep[0] > 0  ? timestep[0]
                                            : 1.0;
    health.steps += steps;
    health.unconverged_steps += std::round((1 - converged[row]) * steps);
  }
  health.unconverged_fraction = health.unconverged_steps / health.steps;
  health.sweeps_median = quantile(sweeps, 0.5);
  health.sweeps_p99 = quantile(sweeps, 0.99);
  health.overlap_max_d = *std::max_element(overlap.begin(), overlap.end());
  return health;
}

SolverRecord read_solver_record(const std::string& directory)
{
  SolverRecord record;
  record.solver_file = (std::filesystem::path(directory) / kSolverFile).string();
  record.log_file = (std::filesystem::path(directory) / kLogFile).string();
  // A solver.time of another layout (a deck that averages other outputs, e.g. the soft-sphere
  // comparison's rigid runs) gives no health of its own: the log's solver lines still do.
  record.no_health_why = "no " + record.solver_file;
  if (std::filesystem::exists(record.solver_file)) {
    const ColumnTable table = read_ave_time(record.solver_file);
    if (fix_output_name(table, 1) && fix_output_name(table, 5) && fix_output_name(table, 7))
      record.health = solver_health(table);
    else record.no_health_why = record.solver_file + " holds no fix outputs 1, 5 and 7";
  }
  std::ifstream log(record.log_file);
  record.log_found = static_cast<bool>(log);
  for (std::string line; std::getline(log, line);) {
    if (line.rfind(kExtremesTag, 0) == 0) {  // "SOLVER max_sweeps_per_step S max_interpenetration_d P"
      std::istringstream fields(line.substr(std::string(kExtremesTag).size()));
      std::string key_sweeps, key_overlap;
      double sweeps = 0, overlap = 0;
      if (fields >> key_sweeps >> sweeps >> key_overlap >> overlap && key_sweeps == "max_sweeps_per_step" &&
          key_overlap == "max_interpenetration_d")
        record.largest_sweeps = sweeps, record.largest_overlap_d = overlap;
      continue;
    }
    const auto at = line.find(kLogSolver);
    if (line.rfind(kLogTag, 0) != 0 || at == std::string::npos) continue;
    const auto summary = line.substr(at + std::string(kLogSolver).size());
    if (summary.rfind("0 steps,", 0) != 0) record.log_lines.push_back(summary);  // not a "run 0"
  }
  return record;
}

void add_solver_results(ResultTable& results, const SolverRecord& record)
{
  struct Row {
    const char* name;
    double SolverHealth::*member;
    const char* unit;
    std::string description;
  };
  const std::string interval = "rows of " + std::string(kSolverFile) + " (each the mean over one solver_interval)";
  const std::vector<Row> rows = {
      {"solver_steps", &SolverHealth::steps, "", "steps solver.time covers"},
      {"solver_unconverged_steps", &SolverHealth::unconverged_steps, "",
       "steps whose last solve hit the sweep cap (fix output 7)"},
      {"solver_unconverged_fraction", &SolverHealth::unconverged_fraction, "", "unconverged steps / steps"},
      {"solver_sweeps_median", &SolverHealth::sweeps_median, "", "median sweeps per step over the " + interval},
      {"solver_sweeps_p99", &SolverHealth::sweeps_p99, "",
       "99th percentile of the sweeps per step over the " + interval},
      {"solver_overlap_max", &SolverHealth::overlap_max_d, "d",
       "largest interpenetration, the largest of the " + interval + " of each step's largest (fix output 5)"}};
  for (const auto& row : rows) {
    if (record.health) results.add(row.name, (*record.health).*row.member, row.unit, row.description);
    else
      results.add_not_recorded(row.name, row.unit, row.description + ": not recorded (" + record.no_health_why + ")");
  }
  const std::string extremes = " of any step of the chute run, from the SOLVER line of " + record.log_file;
  const std::string missing = ": not recorded (" + record.log_file + " holds no SOLVER line)";
  if (record.largest_sweeps)
    results.add("solver_sweeps_largest", *record.largest_sweeps, "", "largest sweeps" + extremes);
  else results.add_not_recorded("solver_sweeps_largest", "", "largest sweeps" + extremes + missing);
  if (record.largest_overlap_d)
    results.add("solver_overlap_largest", *record.largest_overlap_d, "d", "largest interpenetration" + extremes);
  else results.add_not_recorded("solver_overlap_largest", "d", "largest interpenetration" + extremes + missing);
  const auto last = record.log_lines.empty() ? std::nullopt : solver_line_numbers(record.log_lines.back());
  const std::string per_step =
      " of the log's last LAMMPS run (in.chute: the chute run), step by step, from its solver line";
  const std::vector<std::pair<const char*, std::string>> log_rows = {
      {"solver_log_steps", "steps"},
      {"solver_log_unconverged_steps", "unconverged steps"},
      {"solver_log_sweeps_median", "median sweeps per step"},
      {"solver_log_sweeps_p99", "99th percentile of the sweeps per step"},
      {"solver_log_sweeps_max", "largest sweeps of a step"}};
  for (size_t i = 0; i < log_rows.size(); ++i) {
    const std::string description = log_rows[i].second + per_step;
    if (last) results.add(log_rows[i].first, (*last)[i], "", description);
    else
      results.add_not_recorded(log_rows[i].first, "",
                               description + ": not recorded (no solver line in " + record.log_file + ")");
  }
}

std::string solver_health_text(const SolverRecord& record)
{
  std::string text;
  if (const auto& h = record.health)
    text = "From " + h->source + " (" + std::to_string(h->rows) +
           " solver_interval means): " + count_text(h->unconverged_steps) + " of " + count_text(h->steps) +
           " steps unconverged (" + number(100 * h->unconverged_fraction) + " %); sweeps per step, median " +
           number(h->sweeps_median) + ", 99th percentile " + number(h->sweeps_p99) +
           " (of the interval means); largest interpenetration " + number(h->overlap_max_d) +
           " d (the largest interval mean of each step's largest).";
  else
    text = "Unconverged steps, sweeps per step and the largest interpenetration: not recorded (" +
           record.no_health_why + ").";
  if (!record.log_found) return text + " The fix's solver lines: not recorded (no " + record.log_file + ").";
  if (record.largest_overlap_d)
    text += " Over every step of the chute run (the log's SOLVER line): largest sweeps " +
            count_text(*record.largest_sweeps) + ", largest interpenetration " + number(*record.largest_overlap_d) +
            " d.";
  else text += " The chute run's largest sweeps and interpenetration: not recorded (no SOLVER line in the log).";
  if (record.log_lines.empty()) return text + " " + record.log_file + " holds no solver line of the fix.";
  text += " The fix's solver line at the end of each LAMMPS run in " + record.log_file +
          ", in order (per step; in.chute's stage all runs the deposition first):";
  for (size_t i = 0; i < record.log_lines.size(); ++i)
    text += "\n" + std::to_string(i + 1) + ". " + record.log_lines[i];
  return text;
}

}  // namespace cdpost
