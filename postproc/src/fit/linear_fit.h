// Linear least squares (GSL) and the fits built on it.
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "signal/statistics.h"

namespace cdpost {

// Fitted parameters. Errors come from the covariance scaled by chi2/dof (the data carry no
// individual errors, so their scatter sets the scale); with dof == 0 there are none.
struct FitResult {
  std::vector<std::string> names;
  std::vector<Estimate> parameters;
  Eigen::MatrixXd covariance;     // of the parameters, scaled like their errors; empty when dof == 0
  std::vector<double> residuals;  // observed − fitted, one per point in the order given
  double chi2 = 0;                // sum of squared residuals, in squared data units
  int points = 0;
  int dof = 0;
  const Estimate& operator[](const std::string& name) const;
  std::vector<double> values() const;  // the parameters' values, in order
  double rms_residual() const { return std::sqrt(chi2 / points); }
};

// The correlation coefficient of two parameters, cov(a, b)/(σa σb); none without covariance.
std::optional<double> parameter_correlation(const FitResult& fit, const std::string& a, const std::string& b);

// A quantity computed from a fit's parameters (none where it is undefined).
using ParameterFunction = std::function<std::optional<double>(const std::vector<double>& parameters)>;

// One-sigma error of q(p) by the delta method: var q = gᵀ C g, C the fit's covariance and
// g = ∂q/∂p by central differences with steps of 1e-3 of each parameter's error (q is smooth
// on that scale). None without covariance or where q is undefined at a step.
std::optional<double> propagated_error(const FitResult& fit, const ParameterFunction& quantity);

// GSL aborts on errors by default; the fits report them as AnalysisError instead.
void use_gsl_error_codes();

// A fit's result from its parameters, the unscaled covariance (J^T J)^-1 and the residuals
// (observed − fitted): errors and covariance scaled by chi2/dof.
FitResult fit_result(std::vector<std::string> names, const std::vector<double>& parameters,
                     const Eigen::MatrixXd& unscaled_covariance, std::vector<double> residuals);

// y ≈ design * p. Needs at least as many points as parameters and a full-rank design.
FitResult fit_linear(const Eigen::MatrixXd& design, const std::vector<double>& y, std::vector<std::string> names);

// y = prefactor * x^exponent, fitted as a line in log-log; x and y must be positive.
struct PowerLaw {
  Estimate prefactor;
  Estimate exponent;
  std::optional<double> correlation;  // Pearson correlation of x and y (3 points or more)
  int points = 0;
  FitResult line;  // ln y = ln c + n ln x: parameters log_prefactor, exponent and their covariance
};
PowerLaw fit_power_law(const std::vector<double>& x, const std::vector<double>& y);

// y = intercept + slope x weighted by the points' own one-sigma errors (w = 1/sigma^2). The
// slope's error is that of the stated errors, scaled by sqrt(chi2/dof) when the points scatter
// more than their errors say (chi2/dof > 1), never shrunk below it: a sign read from it rests on
// whichever is larger, the errors or the scatter.
struct WeightedSlope {
  Estimate slope;
  double reduced_chi2 = 0;  // chi2/dof of the weighted residuals
  int points = 0;
};
// At least 3 points, every sigma positive, x not all equal.
WeightedSlope fit_weighted_slope(const std::vector<double>& x, const std::vector<double>& y,
                                 const std::vector<double>& sigma);

}  // namespace cdpost
