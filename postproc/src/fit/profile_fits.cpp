#include "fit/profile_fits.h"

#include <gsl/gsl_statistics_double.h>

#include <cmath>

namespace cdpost {

namespace {
double bagnold_shape(double z, double h)
{
  return std::pow(h, 1.5) - std::pow(h - z, 1.5);
}
}  // namespace

BagnoldFit fit_bagnold(const std::vector<double>& z, const std::vector<double>& u, double h)
{
  if (!(h > 0)) throw AnalysisError("the Bagnold fit needs a positive layer thickness h");
  std::vector<double> rows_z, rows_u;
  for (size_t i = 0; i < z.size(); ++i)
    if (z[i] >= 0 && z[i] <= h) {
      rows_z.push_back(z[i]);
      rows_u.push_back(u[i]);
    }
  if (rows_z.size() < 3) throw AnalysisError("the Bagnold fit needs at least 3 profile points in 0 <= z <= h");
  Eigen::MatrixXd design(rows_z.size(), 2);
  for (size_t i = 0; i < rows_z.size(); ++i) {
    design(static_cast<Eigen::Index>(i), 0) = 1.0;
    design(static_cast<Eigen::Index>(i), 1) = bagnold_shape(rows_z[i], h);
  }
  auto fit = fit_linear(design, rows_u, {"slip", "amplitude"});
  BagnoldFit bagnold{fit["slip"], fit["amplitude"], h, 0, fit.points};
  double total = gsl_stats_tss(rows_u.data(), 1, rows_u.size());
  bagnold.r_squared = total > 0 ? 1 - fit.chi2 / total : 1;
  return bagnold;
}

double bagnold_velocity(const BagnoldFit& fit, double z)
{
  return fit.slip.value + fit.amplitude.value * bagnold_shape(std::min(z, fit.h), fit.h);
}

ExponentialFit fit_exponential(const std::vector<double>& z, const std::vector<double>& y)
{
  if (z.size() != y.size() || z.size() < 3) throw AnalysisError("an exponential fit needs at least 3 points");
  Eigen::MatrixXd design(z.size(), 2);
  std::vector<double> log_y;
  for (size_t i = 0; i < z.size(); ++i) {
    if (!(y[i] > 0)) throw AnalysisError("an exponential fit needs positive values");
    design(static_cast<Eigen::Index>(i), 0) = 1.0;
    design(static_cast<Eigen::Index>(i), 1) = z[i];
    log_y.push_back(std::log(y[i]));
  }
  ExponentialFit fit;
  fit.raw = fit_linear(design, log_y, {"log_y0", "inverse_length"});
  fit.inverse_length = fit.raw["inverse_length"];
  const auto& log_y0 = fit.raw["log_y0"];
  fit.y0.value = std::exp(log_y0.value);
  if (log_y0.error) fit.y0.error = fit.y0.value * *log_y0.error;
  return fit;
}

Estimate decay_length(const Estimate& inverse_length)
{
  if (!(inverse_length.value > 0)) throw AnalysisError("decay_length: the slope is not positive");
  Estimate lambda{1.0 / inverse_length.value, std::nullopt};
  if (inverse_length.error) lambda.error = *inverse_length.error / (inverse_length.value * inverse_length.value);
  return lambda;
}

DepthDecay fit_depth_decay(const std::vector<double>& z, const std::vector<double>& amplitude, double h)
{
  double spacing = INFINITY;  // between neighbouring layers; empty layers may be missing
  for (size_t i = 0; i + 1 < z.size(); ++i) spacing = std::min(spacing, std::abs(z[i + 1] - z[i]));
  const double half = spacing / 2, slack = 1e-6 * spacing;  // a layer may start exactly at z = 0
  std::vector<double> rows_z, rows_a;
  for (size_t i = 0; i < z.size(); ++i)
    if (z[i] - half >= -slack && z[i] + half <= h + slack) {
      if (!(amplitude[i] > 0))
        throw AnalysisError("the layer at z = " + format_estimate(z[i], std::nullopt) + " d has no amplitude at f");
      rows_z.push_back(z[i]);
      rows_a.push_back(amplitude[i]);
    }
  if (rows_z.size() < 3)
    throw AnalysisError(std::to_string(rows_z.size()) +
                        " layers lie wholly between z = 0 and the surface, a decay length needs 3");
  auto fit = fit_exponential(rows_z, rows_a);
  const auto& slope = fit.inverse_length;
  if (!(slope.error && slope.value > 2 * *slope.error))
    throw AnalysisError(
        "the amplitude does not decay with depth by more than twice the error of the slope (1/lambda = " +
        format_estimate(slope.value, slope.error) + " per d)");
  return {decay_length(slope), fit.raw.points, fit.raw.rms_residual()};
}

}  // namespace cdpost
