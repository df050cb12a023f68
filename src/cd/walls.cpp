#include "cd/walls.h"

#include <algorithm>
#include <cmath>

namespace cd {

std::optional<WallContact> wall_contact(const Wall& wall, int body, const Disk& disk, double alert,
                                        const PeriodicBox& box)
{
  const double ex = wall.bx - wall.ax;
  const double ey = wall.by - wall.ay;
  const double length_sq = ex * ex + ey * ey;
  double rx = disk.x - wall.ax;
  double ry = disk.y - wall.ay;
  const PeriodicBox::Shift shift = box.minimum_image(rx, ry);

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
  // The disk meets the wall's image `shift` edge vectors away.
  ContactGeometry geometry = disk_world_geometry(body, disk, dx, dy, left_nx, left_ny);
  box.image_velocity(shift, geometry.image_vx, geometry.image_vy);
  return WallContact{geometry, part};
}

double SurfaceMotion::speed_bound(double x, double y, double distance) const
{
  const double lever = std::hypot(x - centre_x, y - centre_y) + distance;
  return std::hypot(vx, vy) + std::fabs(spin) * lever;
}

}  // namespace cd
