#include "fit/profile_fits.h"

#include <gsl/gsl_statistics_double.h>

#include <cmath>

namespace cdpost {

namespace {
double bagnold_shape(double z, double h) { return std::pow(h, 1.5) - std::pow(h - z, 1.5); }
}  // namespace

BagnoldFit fit_bagnold(const std::vector<double>& z, const std::vector<double>& u, double h) {
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

double bagnold_velocity(const BagnoldFit& fit, double z) {
  return fit.slip.value + fit.amplitude.value * bagnold_shape(std::min(z, fit.h), fit.h);
}

CreepFit fit_creep(const std::vector<double>& z, const std::vector<double>& u, double z_min) {
  std::vector<double> rows_z, log_u;
  for (size_t i = 0; i < z.size(); ++i)
    if (z[i] < 0 && z[i] >= z_min && u[i] > 0) {
      rows_z.push_back(z[i]);
      log_u.push_back(std::log(u[i]));
    }
  if (rows_z.size() < 3) throw AnalysisError("the creep fit needs at least 3 points with z < 0 and u > 0");
  Eigen::MatrixXd design(rows_z.size(), 2);
  for (size_t i = 0; i < rows_z.size(); ++i) {
    design(static_cast<Eigen::Index>(i), 0) = 1.0;
    design(static_cast<Eigen::Index>(i), 1) = rows_z[i];
  }
  auto fit = fit_linear(design, log_u, {"log_u0", "inverse_lambda"});
  const auto& inverse_lambda = fit["inverse_lambda"];
  if (!(inverse_lambda.value > 0)) throw AnalysisError("the bed velocity does not decay with depth: no creep length");
  CreepFit creep;
  creep.lambda.value = 1.0 / inverse_lambda.value;
  if (inverse_lambda.error) creep.lambda.error = *inverse_lambda.error / (inverse_lambda.value * inverse_lambda.value);
  creep.u0.value = std::exp(fit["log_u0"].value);
  if (fit["log_u0"].error) creep.u0.error = creep.u0.value * *fit["log_u0"].error;
  creep.points = fit.points;
  return creep;
}

}  // namespace cdpost
