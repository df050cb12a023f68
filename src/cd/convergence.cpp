#include "cd/convergence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cd {

double SweepChange::residual(ConvergenceNorm norm) const
{
  if (sum_change_sq == 0.0) return 0.0;
  if (sum_scale_sq == 0.0) return std::numeric_limits<double>::infinity();
  switch (norm) {
    case ConvergenceNorm::quadratic: return std::sqrt(sum_change_sq / sum_scale_sq);
    case ConvergenceNorm::maximum: return max_change / (sum_scale / contacts);
  }
  return std::numeric_limits<double>::infinity();
}

double SweepChange::quiet_change_sq(ConvergenceNorm norm, double tolerance, double fraction) const
{
  if (contacts == 0.0) return 0.0;
  const double limit = fraction * tolerance;
  switch (norm) {
    case ConvergenceNorm::quadratic: return limit * limit * sum_scale_sq / contacts;
    case ConvergenceNorm::maximum: return limit * limit * (sum_scale / contacts) * (sum_scale / contacts);
  }
  return 0.0;
}

}  // namespace cd
