#include "cd/walls.h"

#include <algorithm>
#include <cmath>

namespace cd {

void PeriodicBox::minimum_image(double& dx, double& dy) const
{
  if (periodic_x) dx -= length_x * std::nearbyint(dx / length_x);
  if (periodic_y) dy -= length_y * std::nearbyint(dy / length_y);
}

std::optional<WallContact> wall_contact(const Wall& wall, int body, const Disk& disk, double alert,
                                        const PeriodicBox& box)
{
  const double ex = wall.bx - wall.ax;
  const double ey = wall.by - wall.ay;
  const double length_sq = ex * ex + ey * ey;
  double rx = disk.x - wall.ax;
  double ry = disk.y - wall.ay;
  box.minimum_image(rx, ry);

  // Parameter of the nearest point along the wall; a segment clamps it to its ends.
  double s = (rx * ex + ry * ey) / length_sq;
  WallPart part = WallPart::interior;
  if (wall.shape == Wall::Shape::segment) {
    if (s <= 0.0) part = WallPart::end_a;
    else if (s >= 1.0) part = WallPart::end_b;
    s = std::clamp(s, 0.0, 1.0);
  }
  const double dx = rx - s * ex;
  const double dy = ry - s * ey;
  if (dx * dx + dy * dy > (disk.radius + alert) * (disk.radius + alert)) return std::nullopt;

  const double length = std::sqrt(length_sq);
  const double left_nx = -ey / length;
  const double left_ny = ex / length;
  return WallContact{disk_world_geometry(body, disk, dx, dy, left_nx, left_ny), part};
}

}  // namespace cd
