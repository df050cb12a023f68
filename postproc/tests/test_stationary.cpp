#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "signal/stationary.h"
#include "signal/statistics.h"

namespace cdpost {
namespace {

TEST(Stationary, SkipsAnExponentialTransient)
{
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 0.3);
  std::vector<double> t, u;
  for (int i = 0; i < 2000; ++i) {
    t.push_back(i * 0.005);
    u.push_back(10 * (1 - std::exp(-t.back() / 1.0)) + noise(rng));
  }
  auto window = detect_stationary(t, u, {});
  EXPECT_LT(relative_drift(t, u, window), 0.02);
  // After about 4 relaxation times the remaining drift is within 2%.
  EXPECT_GT(t[window.begin], 2.0);
  EXPECT_LT(t[window.begin], 6.0);
  EXPECT_EQ(window.end, u.size());
}

TEST(Stationary, SteadyAccelerationHasNoStationaryRegime)
{
  std::vector<double> t, u;
  for (int i = 0; i < 500; ++i) {
    t.push_back(i);
    u.push_back(1 + 0.01 * i);
  }
  EXPECT_THROW(detect_stationary(t, u, {}), AnalysisError);
  auto window = window_between(t, 100, 199.5);
  EXPECT_EQ(window.begin, 100u);
  EXPECT_EQ(window.end, 200u);
}

TEST(Statistics, BlockMeanErrorCoversTheTruth)
{
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0, 1);
  std::vector<double> x;
  for (int i = 0; i < 10000; ++i) x.push_back(3 + noise(rng));
  auto estimate = block_mean(x, 0, x.size());
  ASSERT_TRUE(estimate.error);
  EXPECT_NEAR(*estimate.error, 0.01, 0.005);
  EXPECT_NEAR(estimate.value, 3, 3 * *estimate.error);
  EXPECT_THROW(block_mean(x, 0, 5), AnalysisError);
}

}  // namespace
}  // namespace cdpost
