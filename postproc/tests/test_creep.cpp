// The creep measure (fit/creep.h) on synthetic bed profiles of known lambda(z) above a noise
// floor that changes sign, as the solver's does in the deep bed.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "analysis/creep_results.h"
#include "fit/creep.h"
#include "fit/profile_fits.h"

namespace cdpost {
namespace {

struct Profile {
  std::vector<double> z, u;
};

// Bins of `width` d from -30 d to 0 (centres), u = truth(z) times log-normal noise of
// `relative` plus Gaussian noise of `floor` sqrt(g d); one flowing bin above z = 0.
Profile bed_profile(const std::function<double(double)>& truth, double width, double relative, double floor,
                    unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  Profile p;
  for (double z = -30 + width / 2; z < 0; z += width) {
    p.z.push_back(z);
    p.u.push_back(truth(z) * std::exp(relative * gauss(rng)) + floor * gauss(rng));
  }
  p.z.push_back(width / 2);
  p.u.push_back(2.0);
  return p;
}

// lambda's error from log-normal noise `relative` on `points` bins `width` apart (the slope's
// error of an unweighted line, propagated to 1/slope).
double expected_error(double lambda, double relative, int points, double width)
{
  const double sxx = width * width * points * (points * points - 1.0) / 12;
  return lambda * lambda * relative / std::sqrt(sxx);
}

TEST(Creep, SingleExponentialAboveASignChangingFloor)
{
  const double lambda = 1.5, u0 = 1.4, floor = 4e-5, relative = 0.03;
  const auto p = bed_profile([&](double z) { return u0 * std::exp(z / lambda); }, 1.0, relative, floor, 7);
  const auto creep = measure_creep(p.z, p.u, {});
  ASSERT_TRUE(creep.floor);
  EXPECT_GT(creep.floor->bins, 10);
  // The rms of >= 10 Gaussian values lies within a factor 1.6 of sigma (chi, 10 dof: > 99.9 %).
  EXPECT_GT(creep.floor->value, floor / 1.6);
  EXPECT_LT(creep.floor->value, floor * 1.6);
  ASSERT_TRUE(creep.lambda) << creep.verdict;
  EXPECT_TRUE(creep.verdict.empty());
  EXPECT_EQ(creep.z_high, -0.5);
  // The range ends where the true u crosses 10 x the estimated floor, to a bin.
  const double crossing = lambda * std::log(kFloorMultiple * creep.floor->value / u0);
  EXPECT_NEAR(creep.z_low, crossing, 1.0);
  EXPECT_EQ(creep.points, static_cast<int>(-creep.z_low + 0.5));
  ASSERT_TRUE(creep.lambda->error);
  EXPECT_NEAR(creep.lambda->value, lambda, 3 * *creep.lambda->error);
  EXPECT_LT(*creep.lambda->error, 0.1 * lambda);
  EXPECT_NEAR(creep.u0->value, u0, 3 * *creep.u0->error);

  // The whole-bed fit of every positive bin (cdpost's measure before this one) takes in the
  // floor's points and flattens: far from lambda by its own error, which the range avoids.
  std::vector<double> z, u;
  for (size_t i = 0; i < p.z.size(); ++i)
    if (p.z[i] < 0 && p.u[i] > 0) z.push_back(p.z[i]), u.push_back(p.u[i]);
  const auto whole = decay_length(fit_exponential(z, u).inverse_length);
  EXPECT_GT(whole.value - lambda, 3 * *whole.error);
}

TEST(Creep, LocalDecayLengthFollowsALambdaThatChangesWithDepth)
{
  // lambda 2.2 d down to z = -6 d, 1.1 d below (u continuous), bins of 0.5 d.
  const double upper = 2.2, lower = 1.1, u0 = 1.4, relative = 0.02, floor = 5e-6;
  auto truth = [&](double z) {
    return z > -6 ? u0 * std::exp(z / upper) : u0 * std::exp(-6 / upper + (z + 6) / lower);
  };
  const auto p = bed_profile(truth, 0.5, relative, floor, 11);
  const auto creep = measure_creep(p.z, p.u, {});
  ASSERT_TRUE(creep.lambda) << creep.verdict;
  EXPECT_LT(creep.z_low, -12);  // the bands down to 12 d lie wholly in the range
  EXPECT_GT(creep.lambda->value, lower);
  EXPECT_LT(creep.lambda->value, upper);
  ASSERT_GE(creep.bands.size(), 4u);
  const double expected[] = {upper, upper, lower, lower};
  for (size_t b = 0; b < 4; ++b) {
    const auto& band = creep.bands[b];
    EXPECT_EQ(band.depth_top_d, 3.0 * b);
    EXPECT_EQ(band.depth_bottom_d, 3.0 * (b + 1));
    EXPECT_EQ(band.points, 6);
    ASSERT_TRUE(band.lambda.error);
    EXPECT_GT(*band.lambda.error, 0);
    // Within 3 errors of the truth: the error the noise gives (the fit's own estimate, from 4
    // degrees of freedom, scatters by a factor ~2 about it).
    EXPECT_NEAR(band.lambda.value, expected[b], 3 * expected_error(expected[b], relative, 6, 0.5)) << "band " << b;
  }
  EXPECT_TRUE(creep.band_problems.empty());
}

TEST(Creep, GivenFloorSetsTheRange)
{
  const double lambda = 2.0, u0 = 1.0;
  const auto p = bed_profile([&](double z) { return u0 * std::exp(z / lambda); }, 1.0, 0.01, 1e-6, 3);
  CreepSettings settings;
  settings.floor_reduced = 1e-3;  // 10 x: u > 1e-2, z > 2 ln(1e-2) = -9.2 d
  const auto creep = measure_creep(p.z, p.u, settings);
  ASSERT_TRUE(creep.floor);
  EXPECT_EQ(creep.floor->bins, 0);
  EXPECT_EQ(creep.floor->source(), "given (--creep-floor)");
  EXPECT_EQ(creep.z_low, -8.5);
  EXPECT_EQ(creep.points, 9);
  ASSERT_TRUE(creep.lambda);
  EXPECT_NEAR(creep.lambda->value, lambda, 3 * *creep.lambda->error);
}

TEST(Creep, TooFewResolvedPointsGiveAVerdictNotALambda)
{
  // lambda 0.5 d above a floor of 1e-3: u > 1e-2 only at z = -0.5 and -1.5 d.
  const auto p = bed_profile([](double z) { return 1.4 * std::exp(z / 0.5); }, 1.0, 0.01, 1e-3, 5);
  CreepSettings settings;
  settings.floor_reduced = 1e-3;
  const auto creep = measure_creep(p.z, p.u, settings);
  EXPECT_FALSE(creep.lambda);
  EXPECT_TRUE(creep.bands.empty());
  EXPECT_EQ(creep.points, 2);
  EXPECT_EQ(creep.verdict,
            "unresolved: 2 bins below the wall tops before u first falls below 10 x the floor (0.001 sqrt(g d), given "
            "(--creep-floor)); 4 needed");
  ResultTable results;
  add_creep_results(results, creep);
  EXPECT_TRUE(results.find("creep_floor"));
  EXPECT_EQ(results.find("creep_points")->value, 2);
  EXPECT_FALSE(results.find("creep_lambda"));
  EXPECT_EQ(creep_problems(creep), std::vector<std::string>{creep.verdict});
}

TEST(Creep, ADecayWithoutAFloorBelowItNeedsTheFloorGiven)
{
  const auto p = bed_profile([](double z) { return std::exp(z / 3); }, 1.0, 0.0, 0.0, 1);
  const auto creep = measure_creep(p.z, p.u, {});
  EXPECT_FALSE(creep.floor);
  EXPECT_FALSE(creep.lambda);
  EXPECT_EQ(creep.verdict,
            "unresolved: u decays without reaching a floor down to z = -29.5 d (fewer than 3 bins below the decay "
            "to estimate it from): give --creep-floor");
  CreepSettings settings;
  settings.floor_reduced = 1e-6;
  const auto given = measure_creep(p.z, p.u, settings);
  ASSERT_TRUE(given.lambda);
  EXPECT_NEAR(given.lambda->value, 3.0, 1e-9);  // no noise: exact
  EXPECT_EQ(given.points, 30);                  // 10 x 1e-6 lies below u(-29.5) = 5.4e-5
}

TEST(Creep, ResultsNameTheRangeFloorAndBands)
{
  const auto p = bed_profile([](double z) { return 1.4 * std::exp(z / 1.5); }, 1.0, 0.03, 4e-5, 7);
  const auto creep = measure_creep(p.z, p.u, {});
  ResultTable results;
  add_creep_results(results, creep);
  for (const char* name : {"creep_floor", "creep_points", "creep_z_high", "creep_z_low", "creep_lambda", "creep_u0",
                           "creep_lambda_band_0_3", "creep_lambda_band_3_6"})
    EXPECT_TRUE(results.find(name)) << name;
  EXPECT_EQ(results.find("creep_lambda")->value, creep.lambda->value);
  EXPECT_NE(results.find("creep_floor")->description.find("estimated: rms of u over the"), std::string::npos);
  for (const auto& row : results.rows()) EXPECT_TRUE(is_creep_result(row.name)) << row.name;
}

TEST(Creep, RefusesBadSettings)
{
  const auto p = bed_profile([](double z) { return std::exp(z); }, 1.0, 0.0, 1e-4, 1);
  for (double bad : {0.0, -1e-4, std::nan("")}) {
    CreepSettings settings;
    settings.floor_reduced = bad;
    EXPECT_THROW(measure_creep(p.z, p.u, settings), AnalysisError) << bad;
  }
  CreepSettings shallow;
  shallow.depth_d = 0;
  EXPECT_THROW(measure_creep(p.z, p.u, shallow), AnalysisError);
}

}  // namespace
}  // namespace cdpost
