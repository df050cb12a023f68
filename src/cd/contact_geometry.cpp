#include "cd/contact_geometry.h"

#include <cmath>

namespace cd {

ContactGeometry disk_disk_geometry(int body_a, const Disk& a, int body_b, const Disk& b)
{
  const double dx = a.x - b.x;
  const double dy = a.y - b.y;
  const double distance = std::sqrt(dx * dx + dy * dy);
  ContactGeometry g;
  g.body_a = body_a;
  g.body_b = body_b;
  g.normal_x = dx / distance;
  g.normal_y = dy / distance;
  g.gap = distance - a.radius - b.radius;
  g.lever_a = a.radius;
  g.lever_b = b.radius;
  return g;
}

ContactGeometry disk_world_geometry(int body_a, const Disk& a, double dx, double dy, double fallback_nx,
                                    double fallback_ny)
{
  const double distance = std::sqrt(dx * dx + dy * dy);
  ContactGeometry g;
  g.body_a = body_a;
  g.body_b = world_body;
  if (distance > 0.0) {
    g.normal_x = dx / distance;
    g.normal_y = dy / distance;
  } else {
    g.normal_x = fallback_nx;
    g.normal_y = fallback_ny;
  }
  g.gap = distance - a.radius;
  g.lever_a = a.radius;
  g.lever_b = 0.0;
  return g;
}

}  // namespace cd
