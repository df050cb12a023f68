// The readings of a run's inertial number (fit/inertial_number.h), the weighted slope of the sign
// tests (fit/linear_fit.h) and the creep's first-decade decay (fit/creep.h), against values
// worked by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "fit/creep.h"
#include "fit/inertial_number.h"
#include "fit/linear_fit.h"

namespace cdpost {
namespace {

// Bins 1 d wide, centres 0.5 ... top - 0.5 d, u = u(z) and phi uniform.
struct BinnedProfile {
  std::vector<double> z, u, phi;
};
BinnedProfile binned(double top, double phi, double (*u)(double))
{
  BinnedProfile p;
  for (double z = 0.5; z < top; z += 1) p.z.push_back(z), p.u.push_back(u(z)), p.phi.push_back(phi);
  return p;
}

TEST(InertialNumber, BagnoldReadingIsTheStatedOneTimesTwoAndAHalfOverRootPhiCos)
{
  // 2.5 x 10 / (40^1.5 sqrt(0.8 x cos 60 deg)) = 25 / (252.98 x 0.63246) = 25 / 160.
  EXPECT_NEAR(bagnold_inertial_number(10, 40, 0.8, 60), 0.15625, 1e-12);
}

TEST(InertialNumber, LocalReadingOfALinearProfileUnderUniformPacking)
{
  const auto p = binned(10, 0.8, [](double z) { return 2 * z; });
  // Shear rate 2 over the bins 3.5 ... 6.5; P = cos 60 deg x 0.8 x (10 - 5) = 2; I = 2 / sqrt(2).
  const auto mid = local_inertial_number(p.z, p.u, p.phi, 5, 1.5, 60);
  EXPECT_EQ(mid.bins, 4);
  EXPECT_NEAR(mid.shear_rate.value, 2, 1e-12);
  EXPECT_NEAR(mid.pressure, 2, 1e-12);
  EXPECT_NEAR(mid.phi, 0.8, 1e-12);
  EXPECT_NEAR(mid.inertial.value, std::sqrt(2.0), 1e-12);
  // Inside a bin, its part above counts: 0.5 x 0.8 x 5.25 = 2.1.
  EXPECT_NEAR(local_inertial_number(p.z, p.u, p.phi, 4.75, 1.5, 60).pressure, 2.1, 1e-12);
  EXPECT_THROW(local_inertial_number(p.z, p.u, p.phi, 5, 0.6, 60), AnalysisError);  // 2 bins in the band
  EXPECT_THROW(local_inertial_number(p.z, p.u, p.phi, 12, 3, 60), AnalysisError);   // nothing above
}

TEST(InertialNumber, InABagnoldLayerTheLocalReadingAtMidLayerIsTheBagnoldOne)
{
  // u = a (h^1.5 - (h - z)^1.5): U = 0.6 a h^1.5, and at z = h/2 du/dz = 1.5 a (h/2)^0.5 and
  // P = phi cos theta h/2, so I = 1.5 a / sqrt(phi cos theta) at every depth, as the Bagnold reading.
  constexpr double h = 40, a = 0.08, phi = 0.78, theta = 24;
  const auto p = binned(h, phi, [](double z) { return a * (std::pow(h, 1.5) - std::pow(h - z, 1.5)); });
  const double bagnold = bagnold_inertial_number(0.6 * a * std::pow(h, 1.5), h, phi, theta);
  EXPECT_NEAR(bagnold, 1.5 * a / std::sqrt(phi * std::cos(theta * M_PI / 180)), 1e-12);
  const auto local = local_inertial_number(p.z, p.u, p.phi, h / 2, h / 10, theta);
  EXPECT_NEAR(local.inertial.value / bagnold, 1, 2e-3);  // the line over h/2 +- h/10 of a curved profile
}

TEST(WeightedSlope, EqualErrorsGiveTheLeastSquaresLine)
{
  // x 0, 1, 2; y 0, 1, 3: slope 3/2, intercept -1/6, residuals 1/6, -1/3, 1/6, chi2 1/6 (sigma 1).
  const std::vector<double> x{0, 1, 2}, y{0, 1, 3};
  const auto stated = fit_weighted_slope(x, y, {1, 1, 1});
  EXPECT_NEAR(stated.slope.value, 1.5, 1e-12);
  EXPECT_NEAR(stated.reduced_chi2, 1.0 / 6, 1e-12);
  EXPECT_NEAR(*stated.slope.error, std::sqrt(0.5), 1e-12);  // sqrt(S/Delta) = sqrt(3/6): errors larger than scatter
  // Errors of 0.1: chi2/dof 100/6 > 1, so the error is the scatter's, sqrt(chi2_1/dof/Sxx) = sqrt(1/12).
  const auto scattered = fit_weighted_slope(x, y, {0.1, 0.1, 0.1});
  EXPECT_NEAR(*scattered.slope.error, std::sqrt(1.0 / 12), 1e-12);
  EXPECT_THROW(fit_weighted_slope({1, 1, 1}, y, {1, 1, 1}), AnalysisError);
}

TEST(WeightedSlope, APreciseRunOutweighsTheOthers)
{
  // Two loose points (0, 0), (1, 1) and a precise one at (2, 4): the line goes through (2, 4),
  // y = 4 + b (x - 2), with b minimising (2b - 4)^2 + (b - 3)^2: b = 2.2.
  const auto fit = fit_weighted_slope({0, 1, 2}, {0, 1, 4}, {1, 1, 1e-3});
  EXPECT_NEAR(fit.slope.value, 2.2, 1e-5);
}

TEST(CreepGuideLine, FirstDecadeOfASingleExponential)
{
  // u = exp(z/2) below the wall tops: u(-0.5) / 10 is reached at z = -0.5 - 2 ln 10 = -5.1 d, so
  // the bins -0.5 ... -4.5 make the decade, and lambda is 2.
  std::vector<double> z, u;
  for (double zc = -29.5; zc < 1; zc += 1) z.push_back(zc), u.push_back(zc < 0 ? std::exp(zc / 2) : 3.0);
  const auto decade = first_decade_decay(z, u);
  ASSERT_TRUE(decade);
  EXPECT_EQ(decade->points, 5);
  EXPECT_NEAR(decade->depth_bottom_d, 4.5, 1e-12);
  EXPECT_NEAR(decade->lambda.value, 2, 1e-9);
}

TEST(CreepGuideLine, AProfileSteepeningWithDepthIsReadAtItsTop)
{
  // lambda 2.5 d down to -4 d, 1 d below: the decade below u(-0.5) holds the bins -0.5 ... -4.5 d,
  // four on the 2.5 d branch and one on the 1 d branch: ln u = -0.2, -0.6, -1.0, -1.4, -2.1 against
  // z, whose least-squares slope is 0.46 (lambda 50/23 d); a fit down to the floor would be near 1 d.
  std::vector<double> z, u;
  for (double zc = -29.5; zc < 0; zc += 1)
    z.push_back(zc), u.push_back(zc > -4 ? std::exp(zc / 2.5) : std::exp(-4 / 2.5 + (zc + 4) / 1.0));
  const auto decade = first_decade_decay(z, u);
  ASSERT_TRUE(decade);
  EXPECT_EQ(decade->points, 5);
  EXPECT_NEAR(decade->lambda.value, 50.0 / 23, 1e-9);
  // No decay at the top: none.
  EXPECT_FALSE(first_decade_decay({-1.5, -0.5}, {1, 0.5}));
}

}  // namespace
}  // namespace cdpost
