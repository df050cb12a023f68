// A run's solver health, which every report states: from solver.time (inputs/in.chute: fix
// ave/time of fix contact/dynamics's outputs, each row the means over the steps of one
// solver_interval) the unconverged steps and their fraction, the sweeps per step and the largest
// interpenetration; from log.lammps the fix's end-of-run solver lines (the deposition's too).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/ave_time.h"
#include "output/results.h"

namespace cdpost {

struct SolverHealth {
  std::string source;  // the solver.time read
  size_t rows = 0;
  double steps = 0;  // steps its rows cover (TimeStep differences; the first row's as the second's)
  double unconverged_steps = 0;
  double unconverged_fraction = 0;
  // Median and 99th percentile (nearest rank) of the rows' mean sweeps per step.
  double sweeps_median = 0, sweeps_p99 = 0;
  // The largest of the rows' means of the steps' largest interpenetration (d): a lower bound of
  // the largest any step had (the log's SOLVER line gives that one).
  double overlap_max_d = 0;
};

// From the columns TimeStep, f_ID[1] (sweeps), f_ID[5] (largest interpenetration, d) and f_ID[7]
// (fraction of converged steps) of a solver.time, whatever the fix's ID. InputError naming the
// file (and the line) for a missing column, a converged fraction outside [0, 1], TimeStep not
// increasing or a file without rows.
SolverHealth solver_health(const ColumnTable& table);

// The run folder's solver health: solver.time's (nothing when it is absent or lacks outputs 1, 5
// and 7) and the fix's
// solver lines of log.lammps (the text after "solver: ", one per LAMMPS run; empty without them).
struct SolverRecord {
  std::string solver_file, log_file;  // the paths looked at
  std::optional<SolverHealth> health;
  std::string no_health_why;  // without health: no solver.time, or one of another layout
  bool log_found = false;
  std::vector<std::string> log_lines;
  // The last "SOLVER max_sweeps_per_step S max_interpenetration_d P" line of the log
  // (inputs/in.chute, the chute run's extremes over every step).
  std::optional<double> largest_sweeps, largest_overlap_d;
};
SolverRecord read_solver_record(const std::string& directory);

// Rows solver_steps, solver_unconverged_steps, solver_unconverged_fraction, solver_sweeps_median,
// solver_sweeps_p99 and solver_overlap_max: numbers, or "not recorded" without a solver.time;
// solver_sweeps_largest and solver_overlap_largest from the log's SOLVER line, or "not recorded";
// solver_log_steps, solver_log_unconverged_steps, solver_log_sweeps_median, solver_log_sweeps_p99
// and solver_log_sweeps_max, step by step, from the log's last solver line (in.chute: the chute
// run's), or "not recorded".
void add_solver_results(ResultTable& results, const SolverRecord& record);

// A count of steps or sweeps as a whole number ("390000", not "3.9e+05").
std::string count_text(double count);

// The report's paragraph: the numbers in words, or what was not recorded, and the log's lines.
std::string solver_health_text(const SolverRecord& record);

}  // namespace cdpost
