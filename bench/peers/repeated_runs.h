// A short solve timed again in the same process (peer_bench --repeat): a solve of a millisecond
// run once in a fresh child is mostly that child's first touches of its memory (copy-on-write
// faults), not the method. Runs are deterministic, so they differ in their times only.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace peers {

// Median of `seconds` (not empty; reordered).
inline double median(std::vector<double>& seconds)
{
  const auto middle = seconds.begin() + static_cast<std::ptrdiff_t>(seconds.size() / 2);
  std::nth_element(seconds.begin(), middle, seconds.end());
  if (seconds.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(seconds.begin(), middle));
}

// `solve` run up to `repeats` times while its runs add up to under `budget` CPU seconds (at
// least once): the last run's outcome, its `seconds` the runs' median and `runs` their number.
template <class Outcome, class Solve>
Outcome repeated(Solve solve, int repeats, double budget)
{
  std::vector<double> seconds;
  Outcome outcome;
  for (double spent = 0.0; static_cast<int>(seconds.size()) < repeats && spent < budget;) {
    outcome = solve();
    seconds.push_back(outcome.seconds);
    spent += outcome.seconds;
  }
  outcome.seconds = median(seconds);
  outcome.runs = static_cast<int>(seconds.size());
  return outcome;
}

}  // namespace peers
