// A run's solver health, step by step: how many steps ended unconverged, the largest norm a
// step ended with, the sweeps per step (median, 99th percentile, largest) and the steps a stall
// rescue took over. What a host reports at the end of a run, beside every result.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cd/solver.h"

namespace cd {

struct SolveSummary {
  std::int64_t steps = 0;
  std::int64_t unconverged = 0;   // steps whose solve met the cap
  std::int64_t rescued = 0;       // steps whose solve stalled and went on relaxed
  std::int64_t restarted = 0;     // of those, steps whose relaxed sweeps stalled too: started again from zero
  std::int64_t block_solved = 0;  // of those, steps whose rescue solved blocks of contacts exactly
  double largest_final_norm = 0.0;
  int median_sweeps = 0;
  int p99_sweeps = 0;  // the smallest count that 99 % of the steps did not exceed
  int max_sweeps = 0;

  double unconverged_fraction() const { return steps > 0 ? static_cast<double>(unconverged) / steps : 0.0; }
};

class SolveStatistics {
 public:
  void record(const SolveReport& step);
  void clear();
  SolveSummary summary() const;

 private:
  std::vector<int> sweeps_;  // per step, in the order recorded
  SolveSummary counts_;      // all but the sweep quantiles
};

// One line: "N steps, U unconverged (F %), largest final norm R, sweeps per step median M,
// 99th percentile P, max X, S rescued from a stall (C started again from zero, B by exact block
// solves)".
std::string describe(const SolveSummary& summary);

}  // namespace cd
