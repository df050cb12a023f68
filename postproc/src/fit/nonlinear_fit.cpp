#include "fit/nonlinear_fit.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <cmath>

namespace cdpost {

namespace {

struct Problem {
  const std::vector<double>* observed;
  const PointModel* model;
};

int residuals(const gsl_vector* x, void* data, gsl_vector* f)
{
  const auto& problem = *static_cast<Problem*>(data);
  std::vector<double> parameters(x->data, x->data + x->size);
  for (size_t i = 0; i < problem.observed->size(); ++i) {
    double r = (*problem.model)(parameters, i) - (*problem.observed)[i];
    if (!std::isfinite(r)) return GSL_EDOM;
    gsl_vector_set(f, i, r);
  }
  return GSL_SUCCESS;
}

struct Workspace {
  gsl_multifit_nlinear_workspace* w;
  ~Workspace() { gsl_multifit_nlinear_free(w); }
};

}  // namespace

FitResult fit_nonlinear(const std::vector<double>& observed, const PointModel& model,
                        const std::vector<double>& initial, std::vector<std::string> names)
{
  use_gsl_error_codes();
  const size_t n = observed.size(), p = initial.size();
  if (n < p)
    throw AnalysisError("a fit of " + std::to_string(p) + " parameters needs at least as many points, got " +
                        std::to_string(n));
  Problem problem{&observed, &model};
  gsl_multifit_nlinear_fdf fdf{};
  fdf.f = residuals;
  fdf.df = nullptr;  // finite differences
  fdf.n = n;
  fdf.p = p;
  fdf.params = &problem;
  gsl_multifit_nlinear_parameters settings = gsl_multifit_nlinear_default_parameters();
  Workspace work{gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &settings, n, p)};
  std::vector<double> start = initial;
  gsl_vector_view x0 = gsl_vector_view_array(start.data(), p);
  if (gsl_multifit_nlinear_init(&x0.vector, &fdf, work.w) != GSL_SUCCESS)
    throw AnalysisError("nonlinear fit: the model cannot be evaluated at the initial guess");
  int info = 0;
  int status = gsl_multifit_nlinear_driver(500, 1e-10, 1e-10, 0.0, nullptr, nullptr, &info, work.w);
  if (status != GSL_SUCCESS)
    throw AnalysisError(std::string("nonlinear fit did not converge (") + gsl_strerror(status) + ")");

  gsl_vector* x = gsl_multifit_nlinear_position(work.w);
  std::vector<double> parameters(x->data, x->data + p);
  gsl_vector* f = gsl_multifit_nlinear_residual(work.w);
  std::vector<double> residuals;
  for (size_t i = 0; i < n; ++i) residuals.push_back(-gsl_vector_get(f, i));  // f holds fitted − observed
  gsl_matrix* cov = gsl_matrix_alloc(p, p);
  gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(work.w), 0.0, cov);
  Eigen::MatrixXd covariance(p, p);
  for (size_t i = 0; i < p; ++i)
    for (size_t j = 0; j < p; ++j) covariance(i, j) = gsl_matrix_get(cov, i, j);
  gsl_matrix_free(cov);
  for (double v : parameters)
    if (!std::isfinite(v)) throw AnalysisError("nonlinear fit diverged");
  return fit_result(std::move(names), parameters, covariance, std::move(residuals));
}

}  // namespace cdpost
