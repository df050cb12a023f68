#include "signal/statistics.h"

#include <gsl/gsl_statistics_double.h>

#include <cmath>
#include <string>

namespace cdpost {

Estimate block_mean(const std::vector<double>& x, size_t begin, size_t end, int blocks) {
  if (end > x.size() || begin >= end) throw AnalysisError("block_mean: empty sample range");
  const size_t count = end - begin;
  if (blocks < 2 || count < 2 * static_cast<size_t>(blocks))
    throw AnalysisError("too few samples (" + std::to_string(count) + ") for " +
                        std::to_string(blocks) + " averaging blocks");
  const size_t block_length = count / static_cast<size_t>(blocks);
  std::vector<double> block_means;
  for (int b = 0; b < blocks; ++b)
    block_means.push_back(gsl_stats_mean(x.data() + begin + b * block_length, 1, block_length));
  Estimate estimate;
  estimate.value = gsl_stats_mean(x.data() + begin, 1, count);
  estimate.error = gsl_stats_sd(block_means.data(), 1, block_means.size()) / std::sqrt(blocks);
  return estimate;
}

double correlation(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 3)
    throw AnalysisError("correlation needs two series of at least 3 points");
  return gsl_stats_correlation(x.data(), 1, y.data(), 1, x.size());
}

}  // namespace cdpost
