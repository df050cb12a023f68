#include "signal/statistics.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace cdpost {

Estimate block_mean(const std::vector<double>& x, size_t begin, size_t end, int blocks)
{
  if (end > x.size() || begin >= end) throw AnalysisError("block_mean: empty sample range");
  const size_t count = end - begin;
  if (blocks < 2 || count < 2 * static_cast<size_t>(blocks))
    throw AnalysisError("too few samples (" + std::to_string(count) + ") for " + std::to_string(blocks) +
                        " averaging blocks");
  const size_t block_length = count / static_cast<size_t>(blocks);
  std::vector<double> block_means;
  for (int b = 0; b < blocks; ++b)
    block_means.push_back(gsl_stats_mean(x.data() + begin + b * block_length, 1, block_length));
  Estimate estimate;
  estimate.value = gsl_stats_mean(x.data() + begin, 1, count);
  estimate.error = gsl_stats_sd(block_means.data(), 1, block_means.size()) / std::sqrt(blocks);
  return estimate;
}

double correlation(const std::vector<double>& x, const std::vector<double>& y)
{
  if (x.size() != y.size() || x.size() < 3) throw AnalysisError("correlation needs two series of at least 3 points");
  auto constant = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [&](double e) { return e == v[0]; });
  };
  if (constant(x) || constant(y)) throw AnalysisError("correlation is undefined: one of the series is constant");
  return gsl_stats_correlation(x.data(), 1, y.data(), 1, x.size());
}

double correlation_p_value(double r, int n)
{
  if (n < 3) throw AnalysisError("a p-value of a correlation needs at least 3 points");
  if (!(std::abs(r) < 1)) return 0;  // a perfect correlation (or rounding past it)
  const double dof = n - 2;
  const double t = std::abs(r) * std::sqrt(dof / (1 - r * r));
  return 2 * gsl_cdf_tdist_Q(t, dof);
}

CorrelationTest test_correlation(const std::vector<double>& x, const std::vector<double>& y)
{
  CorrelationTest test;
  test.r = correlation(x, y);
  test.n = static_cast<int>(x.size());
  test.p_value = correlation_p_value(test.r, test.n);
  return test;
}

std::string format_estimate(double value, const std::optional<double>& error)
{
  char buffer[96];
  if (!error || *error <= 0) {
    std::snprintf(buffer, sizeof buffer, "%.5g", value);
    return buffer;
  }
  // Two significant digits of the error, the value to the same decimal place.
  int decimals = std::max(0, 1 - static_cast<int>(std::floor(std::log10(*error))));
  if (decimals > 8 || std::abs(value) >= 1e6) std::snprintf(buffer, sizeof buffer, "%.4g ± %.2g", value, *error);
  else std::snprintf(buffer, sizeof buffer, "%.*f ± %.*f", decimals, value, decimals, *error);
  return buffer;
}

}  // namespace cdpost
