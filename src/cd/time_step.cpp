#include "cd/time_step.h"

#include <cmath>

namespace cd {

double StepGrid::step(int level) const
{
  return std::ldexp(dt_max, -level);
}

long long StepGrid::steps_per_period(int level) const
{
  return static_cast<long long>(steps_per_align) << level;
}

int StepGrid::level_for(double max_speed) const
{
  for (int level = 0; level <= max_level; level++)
    if (max_speed * step(level) <= travel) return level;
  return -1;
}

double StepGrid::period() const
{
  return dt_max * steps_per_align;
}

bool StepGrid::on_alignment(double time) const
{
  const double periods = time / period();
  return std::abs(periods - std::round(periods)) < 1e-9;
}

}  // namespace cd
