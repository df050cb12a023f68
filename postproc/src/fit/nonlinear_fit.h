// Nonlinear least squares with GSL (multifit_nlinear, Levenberg–Marquardt with a
// finite-difference Jacobian).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "fit/linear_fit.h"

namespace cdpost {

// The model's prediction for data point `point` given the parameters.
using PointModel = std::function<double(const std::vector<double>& parameters, size_t point)>;

// Minimises sum (model(p, i) - observed[i])^2 from `initial`. Throws AnalysisError if GSL
// fails or does not converge, or if the result is not finite.
FitResult fit_nonlinear(const std::vector<double>& observed, const PointModel& model,
                        const std::vector<double>& initial, std::vector<std::string> names);

}  // namespace cdpost
