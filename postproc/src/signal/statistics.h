// Time averages with uncertainties that respect the correlation of successive samples.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace cdpost {

// A problem found while analysing data that was read correctly (e.g. no stationary regime).
class AnalysisError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A measured or fitted number and its one-sigma error; no error when none can be given
// (e.g. a fit with as many parameters as points). Units are those of the quantity.
struct Estimate {
  double value = 0;
  std::optional<double> error;
};

// "1.234 ± 0.005", with a precision fitted to the error.
std::string format_estimate(double value, const std::optional<double>& error);

// Mean of x[begin, end) with the standard error of `blocks` consecutive block means
// (block averaging: correct for correlated samples when a block is longer than the
// correlation time). Needs at least 2 samples per block.
Estimate block_mean(const std::vector<double>& x, size_t begin, size_t end, int blocks = 10);

// Pearson correlation coefficient of two equally long series (at least 3 points, neither
// constant: r is undefined then).
double correlation(const std::vector<double>& x, const std::vector<double>& y);

// Two-sided p-value of a Pearson correlation r of n points under no correlation: Student's t
// = r sqrt((n-2)/(1-r^2)) with n-2 degrees of freedom (GSL). Needs n >= 3; |r| = 1 gives 0.
double correlation_p_value(double r, int n);

// r, n and its p-value together.
struct CorrelationTest {
  double r = 0;
  int n = 0;
  double p_value = 1;
};
CorrelationTest test_correlation(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace cdpost
