#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "fit/flow_rules.h"
#include "fit/profile_fits.h"

namespace cdpost {
namespace {

// |fitted - truth| within 3 of its error (and the error exists).
void expect_recovers(const Estimate& fitted, double truth, const char* what)
{
  ASSERT_TRUE(fitted.error) << what;
  EXPECT_NEAR(fitted.value, truth, 3 * *fitted.error) << what;
  EXPECT_LT(*fitted.error, 0.2 * std::abs(truth)) << what;
}

TEST(ProfileFits, BagnoldRecoversSlipAndAmplitude)
{
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

// Runs of one friction coefficient following a rule, with noise on the measured I.
std::vector<FlowPoint> series(double mu, const std::vector<double>& angles, const std::function<double(double)>& rule_i,
                              unsigned seed)
{
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

// a(z) = 0.2 exp((z - h)/15) with 3 % log-normal noise in the flowing layer, layers 10 d apart,
// h = 42 d; two bed layers far below the exponential and one astride the surface must be left out.
TEST(ProfileFits, DepthDecayRecoversTheDecayLength)
{
  std::mt19937 rng(13);
  std::normal_distribution<double> noise(0, 0.03);
  const double h = 42, lambda = 15;
  std::vector<double> z, a;
  for (double zi = -15; zi <= 45; zi += 10) {
    z.push_back(zi);
    a.push_back(zi < 0 ? 1e-5 : zi < 40 ? 0.2 * std::exp((zi - h) / lambda) * std::exp(noise(rng)) : 5.0);
  }
  auto decay = fit_depth_decay(z, a, h);
  EXPECT_EQ(decay.layers, 4);
  expect_recovers(decay.lambda, lambda, "lambda");
  // rms = 0.03 sqrt(chi2_2 / 4); chi2 with 2 degrees of freedom lies in (0.002, 13.8) with 99.8 % probability.
  EXPECT_GT(decay.log_rms_residual, 0.03 * std::sqrt(0.002 / 4));
  EXPECT_LT(decay.log_rms_residual, 0.03 * std::sqrt(13.8 / 4));
}

TEST(ProfileFits, DepthDecayRefusesProfilesWithoutAResolvedDecay)
{
  std::mt19937 rng(14);
  std::normal_distribution<double> noise(0, 0.1);
  std::vector<double> z{-5, 5, 15, 25, 35}, flat;
  for (size_t i = 0; i < z.size(); ++i) flat.push_back(0.05 * std::exp(noise(rng)));
  EXPECT_THROW(fit_depth_decay(z, flat, 42), AnalysisError);  // no decay beyond the noise
  std::vector<double> decaying;
  for (double zi : z) decaying.push_back(std::exp(zi / 10));
  EXPECT_NO_THROW(fit_depth_decay(z, decaying, 42));
  EXPECT_THROW(fit_depth_decay(z, decaying, 28), AnalysisError);  // 2 layers wholly in the flowing layer
  decaying[1] = 0;
  EXPECT_THROW(fit_depth_decay(z, decaying, 42), AnalysisError);  // a layer without amplitude
}

TEST(FlowRules, PouliquenRecoversAnglesAndLength)
{
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
  // Three runs at two angles do not fix three parameters.
  EXPECT_THROW(fit_pouliquen({points[0], points[1], points[1]}, beta), AnalysisError);
}

// Pouliquen's rule with β = 0.3 and ℓ = 6 (β away from 0.136, so a fit that fell back on it
// would fail): flowing runs with 1 % noise on I, stopped runs with 2 % noise on h_stop.
struct PouliquenTruth {
  double tan1 = std::tan(20 * M_PI / 180), tan2 = std::tan(33 * M_PI / 180), ell = 6, beta = 0.3;
  double h_stop(double theta) const { return -ell * std::log((std::tan(theta * M_PI / 180) - tan1) / (tan2 - tan1)); }
  std::vector<FlowPoint> flowing() const
  {
    auto points = series(
        0.5, {21, 22, 23, 24, 25, 26, 27, 28},
        [&](double t) { return -beta / (ell * std::log((t - tan1) / (tan2 - tan1))); }, 11);
    for (size_t i = 0; i < points.size(); ++i) points[i].run = "flowing" + std::to_string(i);
    return points;
  }
  std::vector<StopPoint> stopped() const
  {
    std::mt19937 rng(12);
    std::normal_distribution<double> noise(0, 0.02);
    std::vector<StopPoint> points;
    for (double theta : {20.5, 21.0, 21.5, 22.0})
      points.push_back({"stopped" + std::to_string(points.size()), 0.5, theta, h_stop(theta) * (1 + noise(rng))});
    return points;
  }
};

TEST(FlowRules, PouliquenBetaFreeRecoversBetaAndEllWithStoppedRuns)
{
  const PouliquenTruth truth;
  auto fit = fit_pouliquen_free(truth.flowing(), truth.stopped());
  ASSERT_TRUE(fit.beta && fit.ell);
  expect_recovers(*fit.beta, truth.beta, "beta");
  expect_recovers(*fit.ell, truth.ell, "ell");
  expect_recovers(fit.ell_over_beta, truth.ell / truth.beta, "ell/beta");
  expect_recovers(fit.angles.theta1_deg, 20, "theta1");
  expect_recovers(fit.angles.theta2_deg, 33, "theta2");
  EXPECT_EQ(fit.stopped_runs, 4);
  ASSERT_EQ(fit.residuals.size(), 12u);  // 8 flowing, then 4 stopped
  EXPECT_EQ(fit.residuals[8].run, "stopped0");
  // The stopped run's residual is its tan θ minus the fitted tan θ_stop(h_stop).
  const auto stop = truth.stopped()[0];
  const double fitted =
      pouliquen_stop_tan(stop.h_stop_d, fit.raw["tan_theta1"].value, fit.raw["tan_theta2"].value, fit.ell->value);
  EXPECT_NEAR(fit.residuals[8].value, std::tan(stop.theta_deg * M_PI / 180) - fitted, 1e-12);
}

TEST(FlowRules, PouliquenBetaFreeWithoutStoppedRunsGivesOnlyTheRatio)
{
  const PouliquenTruth truth;
  const auto flowing = truth.flowing();
  auto fit = fit_pouliquen_free(flowing, {});
  EXPECT_FALSE(fit.beta);
  EXPECT_FALSE(fit.ell);
  expect_recovers(fit.ell_over_beta, truth.ell / truth.beta, "ell/beta");
  // Any fixed beta gives the same rule: l/beta is invariant (to the fit's convergence tolerance).
  auto fixed = fit_pouliquen(flowing, 0.136);
  EXPECT_NEAR(fixed.ell.value / 0.136, fit.ell_over_beta.value, 1e-6 * fit.ell_over_beta.value);
  EXPECT_NEAR(*fixed.ell.error / 0.136, *fit.ell_over_beta.error, 1e-4 * *fit.ell_over_beta.error);
  EXPECT_THROW(fit_pouliquen_free({flowing[0], flowing[1]}, truth.stopped()), AnalysisError);
}

TEST(FlowRules, ResidualsAreObservedMinusFittedPerRun)
{
  const PouliquenTruth truth;
  const auto points = truth.flowing();
  auto fit = fit_pouliquen(points, truth.beta);
  ASSERT_EQ(fit.residuals.size(), points.size());
  double squares = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double fitted = pouliquen_tan(points[i].inertial_number, fit.raw["tan_theta1"].value,
                                        fit.raw["tan_theta2"].value, fit.ell.value, truth.beta);
    EXPECT_EQ(fit.residuals[i].run, points[i].run);
    EXPECT_NEAR(fit.residuals[i].value, std::tan(points[i].theta_deg * M_PI / 180) - fitted, 1e-12);
    squares += fit.residuals[i].value * fit.residuals[i].value;
  }
  EXPECT_NEAR(squares, fit.raw.chi2, 1e-12 * std::max(squares, 1e-30));
  EXPECT_NEAR(fit.raw.rms_residual(), std::sqrt(squares / points.size()), 1e-15);
  // 1 % noise on I moves tan θ by at most dtan/dI * 1 % of I: the rms is of that order, not zero.
  EXPECT_GT(fit.raw.rms_residual(), 1e-5);
  EXPECT_LT(fit.raw.rms_residual(), 5e-3);
}

TEST(FlowRules, MuOfIRecoversSharedI0AndAnglesPerFriction)
{
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
  // A friction whose runs are all at one angle has no theta1, theta2 of its own.
  auto one_angle = series(2.0, {28, 28, 28}, rule(b1, b2), 6);
  points.insert(points.end(), one_angle.begin(), one_angle.end());
  EXPECT_THROW(fit_mu_of_i(points), AnalysisError);
}

TEST(FlowRules, PhiVelocityHasOneSlopeAndOnePhiCPerFriction)
{
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
  ASSERT_EQ(fit.residuals.size(), 15u);  // the run without phi has none
  const double fitted = fit.phi_c[0].second.value - fit.k.value * points[0].velocity;
  EXPECT_NEAR(fit.residuals[0].value, *points[0].phi - fitted, 1e-12);
  ASSERT_EQ(fit.phi_c.size(), 3u);
  expect_recovers(fit.phi_c[2].second, 0.78, "phi_c(2)");
  EXPECT_EQ(fit.raw.points, 15);
}

TEST(FlowRules, PhiInertialHasOneSlopeAndOnePhiCPerFriction)
{
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.001);
  std::vector<FlowPoint> points;
  for (double mu : {0.05, 2.0})
    for (double i : {0.03, 0.05, 0.07, 0.09, 0.11}) {
      FlowPoint p;
      p.mu = mu;
      p.inertial_number = i;
      p.velocity = 1000 * i * i;  // any other abscissa must not enter
      p.phi = (mu == 0.05 ? 0.83 : 0.79) - 0.7 * i + noise(rng);
      points.push_back(p);
    }
  auto fit = fit_phi_inertial(points);
  expect_recovers(fit.k, 0.7, "k_I");
  expect_recovers(fit.phi_c[0].second, 0.83, "phi_c(0.05)");
  expect_recovers(fit.phi_c[1].second, 0.79, "phi_c(2)");
  EXPECT_NEAR(fit.residuals[3].value, *points[3].phi - (fit.phi_c[0].second.value - fit.k.value * 0.09), 1e-12);
}

// The delta method on a line y = a + b x: var y = C_aa + 2 x C_ab + x² C_bb exactly.
TEST(LinearFits, PropagatedErrorOfALineIsItsAnalyticBand)
{
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0, 0.1);
  Eigen::MatrixXd design(12, 2);
  std::vector<double> y;
  for (int i = 0; i < 12; ++i) {
    design(i, 0) = 1, design(i, 1) = i;
    y.push_back(2 + 0.5 * i + noise(rng));
  }
  auto fit = fit_linear(design, y, {"a", "b"});
  for (double x : {-3.0, 4.0, 20.0}) {
    auto error = propagated_error(fit, [&](const std::vector<double>& p) { return p[0] + p[1] * x; });
    const auto& c = fit.covariance;
    ASSERT_TRUE(error);
    EXPECT_NEAR(*error, std::sqrt(c(0, 0) + 2 * x * c(0, 1) + x * x * c(1, 1)), 1e-6 * *error);
  }
  auto corr = parameter_correlation(fit, "a", "b");
  ASSERT_TRUE(corr);
  EXPECT_NEAR(*corr, fit.covariance(0, 1) / (*fit.parameters[0].error * *fit.parameters[1].error), 1e-12);
  EXPECT_LT(*corr, 0);  // x > 0 throughout: a steeper line must start lower
  // Undefined where the quantity is: no error.
  EXPECT_FALSE(propagated_error(fit, [](const std::vector<double>&) { return std::optional<double>(); }));
}

// Two frictions following the mu(I) rule with I0 = 0.3 (θ1, θ2 = 21°, 33° and 15°, 26°) at
// I = 0.03–0.11, as in the series, with 1 % noise on I: there the rule is nearly
// tan θ1 + (tan θ2 − tan θ1) I/I0, and only the slope (tan θ2 − tan θ1)/I0 is well determined.
std::vector<FlowPoint> mu_of_i_runs(unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 0.01);
  std::vector<FlowPoint> points;
  for (auto [mu, theta1, theta2] : {std::tuple{0.5, 21.0, 33.0}, {0.05, 15.0, 26.0}})
    for (double i = 0.03; i < 0.1101; i += 0.01) {
      FlowPoint p;
      p.mu = mu;
      p.inertial_number = i * (1 + noise(rng));
      p.theta_deg =
          std::atan(mu_of_i_tan(i, std::tan(theta1 * M_PI / 180), std::tan(theta2 * M_PI / 180), 0.3)) * 180 / M_PI;
      points.push_back(p);
    }
  return points;
}

TEST(FlowRules, MuOfII0AndTheta2TradeOffAndHeldI0RefitsFindTheTruth)
{
  const auto points = mu_of_i_runs(21);
  auto fit = fit_mu_of_i(points);
  // A larger I0 is made up by a larger θ2 (same slope): strongly positive.
  for (const std::string theta2 : {"tan_theta2_0", "tan_theta2_1"}) {
    auto corr = parameter_correlation(fit.raw, "I0", theta2);
    ASSERT_TRUE(corr);
    EXPECT_GT(*corr, 0.95) << theta2;
  }
  // Held at each value, the rms residual is smallest at the true I0 (0.3) and grows away from it.
  std::vector<double> rms;
  const std::vector<double> held{0.1, 0.15, 0.2, 0.3, 0.4, 0.5};
  for (double i0 : held) {
    auto refit = fit_mu_of_i_held_i0(points, i0);
    EXPECT_EQ(refit.raw.parameters.size(), 4u);  // θ1, θ2 of each friction
    EXPECT_EQ(refit.i0.value, i0);
    EXPECT_FALSE(refit.i0.error);
    rms.push_back(refit.raw.rms_residual());
  }
  EXPECT_EQ(std::min_element(rms.begin(), rms.end()) - rms.begin(), 3);
  EXPECT_GT(rms.front(), 2 * rms[3]);
  EXPECT_THROW(fit_mu_of_i_held_i0(points, 0), AnalysisError);
}

TEST(FlowRules, PouliquenTheta2AndEllTradeOffAndHeldEllRefitsFindTheTruth)
{
  // θ1 = 20°, θ2 = 33°, ℓ = 1.5 at β = 0.136: I = β/(ℓ ln((tan θ2 − tan θ1)/(tan θ − tan θ1))).
  const double tan1 = std::tan(20 * M_PI / 180), tan2 = std::tan(33 * M_PI / 180), ell = 1.5, beta = 0.136;
  auto inverse = [&](double t) { return -beta / (ell * std::log((t - tan1) / (tan2 - tan1))); };
  const auto points = series(0.5, {21, 22, 23, 24, 25, 26, 27, 28}, inverse, 3);
  auto fit = fit_pouliquen(points, beta);
  // A longer ℓ raises tan θ at every I, which a lower θ2 takes back: strongly negative.
  auto corr = parameter_correlation(fit.raw, "tan_theta2", "ell");
  ASSERT_TRUE(corr);
  EXPECT_LT(*corr, -0.9);
  std::vector<double> rms;
  const std::vector<double> held{0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.5};
  for (double value : held) {
    auto refit = fit_pouliquen_held_ell(points, beta, value);
    EXPECT_EQ(refit.raw.parameters.size(), 2u);
    EXPECT_EQ(refit.ell.value, value);
    rms.push_back(refit.raw.rms_residual());
  }
  EXPECT_EQ(std::min_element(rms.begin(), rms.end()) - rms.begin(), 3);
  EXPECT_THROW(fit_pouliquen_held_ell(points, beta, -1), AnalysisError);
}

TEST(LinearFits, PowerLawRecoversExponentAndCorrelation)
{
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

TEST(LinearFits, AsManyPointsAsParametersGivesNoErrors)
{
  Eigen::MatrixXd design(2, 2);
  design << 1, 0, 1, 1;
  auto fit = fit_linear(design, {1, 3}, {"a", "b"});
  EXPECT_NEAR(fit["b"].value, 2, 1e-12);
  EXPECT_FALSE(fit["b"].error.has_value());
}

}  // namespace
}  // namespace cdpost
