#include "cd/convergence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cd {

void SweepChange::add(Local2 velocity_change, Local2 velocity_scale)
{
  const double change_sq = velocity_change.n * velocity_change.n + velocity_change.t * velocity_change.t;
  const double scale_sq = velocity_scale.n * velocity_scale.n + velocity_scale.t * velocity_scale.t;
  sum_change_sq += change_sq;
  sum_scale_sq += scale_sq;
  max_change = std::max(max_change, std::sqrt(change_sq));
  sum_scale += std::sqrt(scale_sq);
  contacts += 1.0;
}

void SweepChange::merge(const SweepChange& other)
{
  sum_change_sq += other.sum_change_sq;
  sum_scale_sq += other.sum_scale_sq;
  max_change = std::max(max_change, other.max_change);
  sum_scale += other.sum_scale;
  contacts += other.contacts;
}

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
