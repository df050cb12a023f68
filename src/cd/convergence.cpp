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

}  // namespace cd
