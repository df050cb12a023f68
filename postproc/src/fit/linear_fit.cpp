#include "fit/linear_fit.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit.h>

#include <algorithm>
#include <cmath>

namespace cdpost {

const Estimate& FitResult::operator[](const std::string& name) const
{
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return parameters[i];
  throw AnalysisError("fit has no parameter '" + name + "'");
}

std::vector<double> FitResult::values() const
{
  std::vector<double> v;
  for (const auto& p : parameters) v.push_back(p.value);
  return v;
}

std::optional<double> parameter_correlation(const FitResult& fit, const std::string& a, const std::string& b)
{
  if (fit.covariance.size() == 0) return std::nullopt;
  auto index = [&](const std::string& name) {
    fit[name];  // throws for an unknown name
    return static_cast<Eigen::Index>(std::find(fit.names.begin(), fit.names.end(), name) - fit.names.begin());
  };
  const Eigen::Index i = index(a), j = index(b);
  const double scale = std::sqrt(fit.covariance(i, i) * fit.covariance(j, j));
  if (!(scale > 0)) return std::nullopt;
  return fit.covariance(i, j) / scale;
}

std::optional<double> propagated_error(const FitResult& fit, const ParameterFunction& quantity)
{
  if (fit.covariance.size() == 0) return std::nullopt;
  const auto centre = fit.values();
  Eigen::VectorXd gradient(static_cast<Eigen::Index>(centre.size()));
  for (size_t i = 0; i < centre.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const double step = 1e-3 * std::sqrt(fit.covariance(k, k));
    if (!(step > 0)) return std::nullopt;
    auto shifted = centre;
    shifted[i] = centre[i] + step;
    const auto up = quantity(shifted);
    shifted[i] = centre[i] - step;
    const auto down = quantity(shifted);
    if (!up || !down) return std::nullopt;
    gradient(k) = (*up - *down) / (2 * step);
  }
  const double variance = gradient.dot(fit.covariance * gradient);
  if (!(std::isfinite(variance) && variance >= 0)) return std::nullopt;
  return std::sqrt(variance);
}

void use_gsl_error_codes()
{
  gsl_set_error_handler_off();
}

FitResult fit_result(std::vector<std::string> names, const std::vector<double>& parameters,
                     const Eigen::MatrixXd& unscaled_covariance, std::vector<double> residuals)
{
  FitResult fit;
  fit.names = std::move(names);
  fit.points = static_cast<int>(residuals.size());
  fit.dof = fit.points - static_cast<int>(parameters.size());
  for (double r : residuals) fit.chi2 += r * r;
  fit.residuals = std::move(residuals);
  if (fit.dof > 0) fit.covariance = unscaled_covariance * (fit.chi2 / fit.dof);
  for (size_t i = 0; i < parameters.size(); ++i) {
    Estimate e{parameters[i], std::nullopt};
    if (fit.dof > 0) {
      double variance = fit.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
      if (std::isfinite(variance) && variance >= 0) e.error = std::sqrt(variance);
    }
    fit.parameters.push_back(e);
  }
  return fit;
}

FitResult fit_linear(const Eigen::MatrixXd& design, const std::vector<double>& y, std::vector<std::string> names)
{
  use_gsl_error_codes();
  const size_t n = static_cast<size_t>(design.rows()), p = static_cast<size_t>(design.cols());
  if (n != y.size() || p != names.size()) throw AnalysisError("fit_linear: inconsistent sizes");
  if (n < p)
    throw AnalysisError("a fit of " + std::to_string(p) + " parameters needs at least as many points, got " +
                        std::to_string(n));
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x = design;
  std::vector<double> y_copy = y;
  gsl_matrix_view x_view = gsl_matrix_view_array(x.data(), n, p);
  gsl_vector_view y_view = gsl_vector_view_array(y_copy.data(), n);
  gsl_vector* c = gsl_vector_alloc(p);
  gsl_matrix* cov = gsl_matrix_alloc(p, p);
  gsl_multifit_linear_workspace* work = gsl_multifit_linear_alloc(n, p);
  size_t rank = 0;
  double chi2 = 0;
  int status = gsl_multifit_linear_tsvd(&x_view.matrix, &y_view.vector, 1e-12, c, cov, &chi2, &rank, work);
  std::vector<double> parameters(c->data, c->data + p);
  Eigen::MatrixXd covariance(p, p);
  for (size_t i = 0; i < p; ++i)
    for (size_t j = 0; j < p; ++j) covariance(i, j) = gsl_matrix_get(cov, i, j);
  gsl_multifit_linear_free(work);
  gsl_matrix_free(cov);
  gsl_vector_free(c);
  if (status != GSL_SUCCESS || rank < p)
    throw AnalysisError("linear fit is degenerate (the data do not determine every parameter)");
  const int dof = static_cast<int>(n - p);
  // gsl returns the covariance already scaled by chi2/dof when dof > 0; undo it for fit_result.
  if (dof > 0 && chi2 > 0) covariance *= dof / chi2;
  Eigen::VectorXd fitted = design * Eigen::Map<const Eigen::VectorXd>(parameters.data(), static_cast<Eigen::Index>(p));
  std::vector<double> residuals;
  for (size_t i = 0; i < n; ++i) residuals.push_back(y[i] - fitted(static_cast<Eigen::Index>(i)));
  return fit_result(std::move(names), parameters, covariance, std::move(residuals));
}

PowerLaw fit_power_law(const std::vector<double>& x, const std::vector<double>& y)
{
  if (x.size() != y.size() || x.size() < 2) throw AnalysisError("a power law needs at least 2 points");
  Eigen::MatrixXd design(x.size(), 2);
  std::vector<double> log_y;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0 && y[i] > 0)) throw AnalysisError("a power-law fit needs positive values");
    design(static_cast<Eigen::Index>(i), 0) = 1.0;
    design(static_cast<Eigen::Index>(i), 1) = std::log(x[i]);
    log_y.push_back(std::log(y[i]));
  }
  auto fit = fit_linear(design, log_y, {"log_prefactor", "exponent"});
  PowerLaw law;
  const auto& log_prefactor = fit.parameters[0];
  law.prefactor.value = std::exp(log_prefactor.value);
  if (log_prefactor.error) law.prefactor.error = law.prefactor.value * *log_prefactor.error;
  law.exponent = fit.parameters[1];
  law.points = fit.points;
  law.line = fit;
  if (x.size() >= 3) law.correlation = correlation(x, y);
  return law;
}

WeightedSlope fit_weighted_slope(const std::vector<double>& x, const std::vector<double>& y,
                                 const std::vector<double>& sigma)
{
  const size_t n = x.size();
  if (n < 3 || y.size() != n || sigma.size() != n) throw AnalysisError("a weighted slope needs 3 points or more");
  double s = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!(sigma[i] > 0)) throw AnalysisError("a weighted slope needs positive errors");
    const double w = 1 / (sigma[i] * sigma[i]);
    s += w, sx += w * x[i], sy += w * y[i], sxx += w * x[i] * x[i], sxy += w * x[i] * y[i];
  }
  const double determinant = s * sxx - sx * sx;
  if (!(determinant > 1e-12 * s * sxx)) throw AnalysisError("a weighted slope needs x that are not all equal");
  const double slope = (s * sxy - sx * sy) / determinant, intercept = (sxx * sy - sx * sxy) / determinant;
  double chi2 = 0;
  for (size_t i = 0; i < n; ++i) chi2 += std::pow((y[i] - intercept - slope * x[i]) / sigma[i], 2);
  WeightedSlope fit;
  fit.points = static_cast<int>(n);
  fit.reduced_chi2 = chi2 / static_cast<double>(n - 2);
  fit.slope = {slope, std::sqrt(s / determinant) * std::max(1.0, std::sqrt(fit.reduced_chi2))};
  return fit;
}

}  // namespace cdpost
