#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fit/flow_rules.h"
#include "fit/profile_fits.h"

namespace cdpost {
namespace {

// |fitted - truth| within 3 of its error (and the error exists).
void expect_recovers(const Estimate& fitted, double truth, const char* what) {
  ASSERT_TRUE(fitted.error) << what;
  EXPECT_NEAR(fitted.value, truth, 3 * *fitted.error) << what;
  EXPECT_LT(*fitted.error, 0.2 * std::abs(truth)) << what;
}

TEST(ProfileFits, BagnoldRecoversSlipAndAmplitude) {
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0, 0.05);
  const double h = 40, slip = 0.5, amplitude = 0.02;
  std::vector<double> z, u;
  for (double zi = -10; zi <= 45; zi += 1) {
    z.push_back(zi);
    u.push_back(zi < 0 ? 0 : slip + amplitude * (std::pow(h, 1.5) - std::pow(h - std::min(zi, h), 1.5)) + noise(rng));
  }
  auto fit = fit_bagnold(z, u, h);
  EXPECT_EQ(fit.points, 41);
  expect_recovers(fit.slip, slip, "slip");
  expect_recovers(fit.amplitude, amplitude, "amplitude");
  EXPECT_GT(fit.r_squared, 0.99);
}

TEST(ProfileFits, CreepRecoversTheDecayLength) {
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0, 0.05);
  std::vector<double> z, u;
  for (double zi = -25.5; zi < 10; zi += 1) {
    z.push_back(zi);
    u.push_back(zi < 0 ? 0.4 * std::exp(zi / 3.0) * std::exp(noise(rng)) : 5.0);
  }
  auto fit = fit_creep(z, u, -30);
  EXPECT_EQ(fit.points, 26);
  expect_recovers(fit.lambda, 3.0, "lambda");
  expect_recovers(fit.u0, 0.4, "u0");
  EXPECT_THROW(fit_creep(z, std::vector<double>(z.size(), -1.0), -30), AnalysisError);
}

// Runs of one friction coefficient following a rule, with noise on the measured I.
std::vector<FlowPoint> series(double mu, const std::vector<double>& angles, const std::function<double(double)>& rule_i,
                              unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 0.01);
  std::vector<FlowPoint> points;
  for (double theta : angles) {
    FlowPoint p;
    p.mu = mu;
    p.theta_deg = theta;
    p.inertial_number = rule_i(std::tan(theta * M_PI / 180)) * (1 + noise(rng));
    p.velocity = p.inertial_number * 300;
    points.push_back(p);
  }
  return points;
}

TEST(FlowRules, PouliquenRecoversAnglesAndLength) {
  const double tan1 = std::tan(20 * M_PI / 180), tan2 = std::tan(33 * M_PI / 180), ell = 1.5, beta = 0.136;
  auto inverse = [&](double t) { return -beta / (ell * std::log((t - tan1) / (tan2 - tan1))); };
  auto points = series(0.5, {21, 22, 23, 24, 25, 26, 27, 28}, inverse, 3);
  auto fit = fit_pouliquen(points, beta);
  expect_recovers(fit.angles.theta1_deg, 20, "theta1");
  expect_recovers(fit.angles.theta2_deg, 33, "theta2");
  expect_recovers(fit.ell, ell, "ell");
  auto i = pouliquen_inertial_number(std::tan(24 * M_PI / 180), fit);
  ASSERT_TRUE(i);
  EXPECT_NEAR(pouliquen_tan(*i, tan1, tan2, ell, beta), std::tan(24 * M_PI / 180), 0.01);
  EXPECT_THROW(fit_pouliquen({points[0], points[1]}, beta), AnalysisError);
}

TEST(FlowRules, MuOfIRecoversSharedI0AndAnglesPerFriction) {
  const double i0 = 0.3;
  auto rule = [&](double t1, double t2) { return [=](double t) { return i0 * (t - t1) / (t2 - t); }; };
  const double a1 = std::tan(15 * M_PI / 180), a2 = std::tan(26 * M_PI / 180);
  const double b1 = std::tan(21 * M_PI / 180), b2 = std::tan(33 * M_PI / 180);
  auto points = series(0.05, {16, 17, 18, 19, 20, 21, 22}, rule(a1, a2), 4);
  auto more = series(0.5, {22, 23, 24, 25, 26, 27, 28}, rule(b1, b2), 5);
  points.insert(points.end(), more.begin(), more.end());
  auto fit = fit_mu_of_i(points);
  expect_recovers(fit.i0, i0, "I0");
  ASSERT_EQ(fit.angles.size(), 2u);
  EXPECT_EQ(fit.angles[1].mu, 0.5);
  expect_recovers(fit.angles[0].theta1_deg, 15, "theta1(0.05)");
  expect_recovers(fit.angles[0].theta2_deg, 26, "theta2(0.05)");
  expect_recovers(fit.angles[1].theta1_deg, 21, "theta1(0.5)");
  expect_recovers(fit.angles[1].theta2_deg, 33, "theta2(0.5)");
}

TEST(FlowRules, PhiVelocityHasOneSlopeAndOnePhiCPerFriction) {
  std::mt19937 rng(6);
  std::normal_distribution<double> noise(0, 0.002);
  std::vector<FlowPoint> points;
  for (double mu : {0.05, 0.5, 2.0})
    for (double u : {5.0, 10.0, 15.0, 20.0, 25.0}) {
      FlowPoint p;
      p.mu = mu;
      p.velocity = u;
      p.phi = (mu == 0.05 ? 0.82 : mu == 0.5 ? 0.80 : 0.78) - 0.003 * u + noise(rng);
      points.push_back(p);
    }
  points.push_back(FlowPoint{});  // a run without phi is left out
  points.back().mu = 7;
  auto fit = fit_phi_velocity(points);
  expect_recovers(fit.k, 0.003, "k");
  ASSERT_EQ(fit.phi_c.size(), 3u);
  expect_recovers(fit.phi_c[2].second, 0.78, "phi_c(2)");
  EXPECT_EQ(fit.raw.points, 15);
}

TEST(LinearFits, PowerLawRecoversExponentAndCorrelation) {
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0, 0.02);
  std::vector<double> x, y;
  for (double xi = 1; xi < 30; xi *= 1.3) {
    x.push_back(xi);
    y.push_back(3 * std::pow(xi, 0.5) * std::exp(noise(rng)));
  }
  auto law = fit_power_law(x, y);
  expect_recovers(law.exponent, 0.5, "exponent");
  expect_recovers(law.prefactor, 3, "prefactor");
  ASSERT_TRUE(law.correlation);
  EXPECT_GT(*law.correlation, 0.95);
  EXPECT_THROW(fit_power_law({1, -2}, {1, 2}), AnalysisError);
}

TEST(LinearFits, AsManyPointsAsParametersGivesNoErrors) {
  Eigen::MatrixXd design(2, 2);
  design << 1, 0, 1, 1;
  auto fit = fit_linear(design, {1, 3}, {"a", "b"});
  EXPECT_NEAR(fit["b"].value, 2, 1e-12);
  EXPECT_FALSE(fit["b"].error.has_value());
}

}  // namespace
}  // namespace cdpost
