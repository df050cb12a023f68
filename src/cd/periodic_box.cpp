// The periodic box (cd/periodic_box.h).
#include "cd/periodic_box.h"

#include <cmath>

namespace cd {

PeriodicBox::Shift PeriodicBox::minimum_image(double& dx, double& dy) const
{
  Shift shift;
  if (periodic_y) {
    shift.y = static_cast<int>(std::nearbyint(dy / length_y));
    dx -= shift.y * tilt_xy;
    dy -= shift.y * length_y;
  }
  if (periodic_x) {
    shift.x = static_cast<int>(std::nearbyint(dx / length_x));
    dx -= shift.x * length_x;
  }
  return shift;
}

PeriodicBox::Shift PeriodicBox::wrapping(double dx, double dy) const
{
  const double along_x = dx - tilt_xy * dy / length_y;
  return {periodic_x ? -static_cast<int>(std::floor(along_x / length_x)) : 0,
          periodic_y ? -static_cast<int>(std::floor(dy / length_y)) : 0};
}

void PeriodicBox::image_velocity(const Shift& shift, double& vx, double& vy) const
{
  vx = shift.x * rate_x + shift.y * rate_xy;
  vy = shift.y * rate_y;
}

PeriodicBox PeriodicBox::advanced(double elapsed) const
{
  PeriodicBox later = *this;
  later.length_x += elapsed * rate_x;
  later.length_y += elapsed * rate_y;
  later.tilt_xy += elapsed * rate_xy;
  return later;
}

}  // namespace cd
