// The p-value of a Pearson correlation against values computed independently of GSL's t
// distribution: printed tables of Student's t, and a Monte Carlo estimate under no correlation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "signal/statistics.h"

namespace cdpost {
namespace {

// r whose t = r sqrt(dof / (1 - r^2)) equals `t`.
double r_of_t(double t, int dof)
{
  return t / std::sqrt(t * t + dof);
}

// Two-sided critical values of Student's t from the printed tables (three decimals). Rounding
// t by 5e-4 moves p by at most 2 x 5e-4 x the t density there, below 0.1: 1e-4.
TEST(Significance, PValueMatchesTheStudentTable)
{
  struct Row {
    int dof;
    double t;
    double p;
  };
  for (const Row& row :
       {Row{1, 12.706, 0.05}, Row{4, 2.776, 0.05}, Row{8, 2.306, 0.05}, Row{8, 3.355, 0.01}, Row{28, 2.048, 0.05}}) {
    EXPECT_NEAR(correlation_p_value(r_of_t(row.t, row.dof), row.dof + 2), row.p, 1e-4) << "dof " << row.dof;
    EXPECT_NEAR(correlation_p_value(-r_of_t(row.t, row.dof), row.dof + 2), row.p, 1e-4) << "two-sided";
  }
}

// The fraction of independent normal samples of 6 pairs with |r| >= 0.7, against the p-value of
// r = 0.7 at n = 6; the estimate's standard error is sqrt(p (1 - p) / N), the tolerance 4 of it.
TEST(Significance, PValueMatchesAMonteCarloEstimate)
{
  std::mt19937 rng(21);
  std::normal_distribution<double> normal(0, 1);
  const int n = 6, trials = 200000;
  const double r0 = 0.7;
  int beyond = 0;
  std::vector<double> x(n), y(n);
  for (int trial = 0; trial < trials; ++trial) {
    for (int i = 0; i < n; ++i) x[i] = normal(rng), y[i] = normal(rng);
    if (std::abs(correlation(x, y)) >= r0) ++beyond;
  }
  const double estimate = static_cast<double>(beyond) / trials;
  const double standard_error = std::sqrt(estimate * (1 - estimate) / trials);
  EXPECT_NEAR(correlation_p_value(r0, n), estimate, 4 * standard_error);
  EXPECT_GT(estimate, 0.05);  // the comparison is not made in a tail where both vanish
}

TEST(Significance, EdgeCases)
{
  EXPECT_EQ(correlation_p_value(1.0, 5), 0.0);
  EXPECT_EQ(correlation_p_value(-1.0, 3), 0.0);
  EXPECT_NEAR(correlation_p_value(0.0, 10), 1.0, 1e-12);
  EXPECT_THROW(correlation_p_value(0.5, 2), AnalysisError);  // no p-value below 3 points
  EXPECT_THROW(test_correlation({1, 2}, {2, 4}), AnalysisError);
  EXPECT_THROW(test_correlation({45, 45, 45}, {1, 2, 3}), AnalysisError);  // r undefined: constant L
  auto test = test_correlation({1, 2, 3, 4}, {1.1, 1.9, 3.2, 3.9});
  EXPECT_EQ(test.n, 4);
  EXPECT_GT(test.r, 0.98);
  EXPECT_NEAR(test.p_value, correlation_p_value(test.r, 4), 1e-15);
}

}  // namespace
}  // namespace cdpost
