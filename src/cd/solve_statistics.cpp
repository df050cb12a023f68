#include "cd/solve_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cd {

void SolveStatistics::record(const SolveReport& step)
{
  sweeps_.push_back(step.iterations);
  ++counts_.steps;
  counts_.unconverged += step.converged ? 0 : 1;
  counts_.rescued += step.stalled_sweeps > 0 ? 1 : 0;
  counts_.restarted += step.cold_restarts > 0 ? 1 : 0;
  counts_.block_solved += step.block_solves > 0 ? 1 : 0;
  counts_.largest_final_norm = std::max(counts_.largest_final_norm, step.residual);
}

void SolveStatistics::clear()
{
  sweeps_.clear();
  counts_ = SolveSummary{};
}

namespace {

// The smallest recorded value that a fraction q of the values do not exceed (nearest rank).
int quantile(std::vector<int>& values, double q)
{
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  const std::size_t index = std::min(values.size() - 1, rank > 0 ? rank - 1 : 0);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
  return values[index];
}

}  // namespace

SolveSummary SolveStatistics::summary() const
{
  SolveSummary summary = counts_;
  if (sweeps_.empty()) return summary;
  std::vector<int> sorted = sweeps_;
  summary.median_sweeps = quantile(sorted, 0.5);
  summary.p99_sweeps = quantile(sorted, 0.99);
  summary.max_sweeps = *std::max_element(sweeps_.begin(), sweeps_.end());
  return summary;
}

std::string describe(const SolveSummary& s)
{
  char line[320];
  std::snprintf(line, sizeof(line),
                "%lld steps, %lld unconverged (%.3g %%), largest final norm %.3g, sweeps per step median %d, "
                "99th percentile %d, max %d, %lld rescued from a stall (%lld started again from zero, %lld by exact "
                "block solves)",
                static_cast<long long>(s.steps), static_cast<long long>(s.unconverged),
                100.0 * s.unconverged_fraction(), s.largest_final_norm, s.median_sweeps, s.p99_sweeps, s.max_sweeps,
                static_cast<long long>(s.rescued), static_cast<long long>(s.restarted),
                static_cast<long long>(s.block_solved));
  return line;
}

}  // namespace cd
