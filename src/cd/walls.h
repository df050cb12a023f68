// Rigid walls of the world: infinite lines and finite segments, in a box that may be periodic.
#pragma once

#include <optional>

#include "cd/contact.h"
#include "cd/contact_geometry.h"

namespace cd {

// Minimum-image convention for the periodic directions of an orthogonal box.
struct PeriodicBox {
  bool periodic_x = false;
  bool periodic_y = false;
  double length_x = 0.0;
  double length_y = 0.0;

  void minimum_image(double& dx, double& dy) const;
};

// Part of a wall that a disk touches; ends of a segment are point contacts of their own.
enum class WallPart : int { interior = 0, end_a = 1, end_b = 2 };

// A line through a and b (shape line, infinite) or the segment from a to b.
struct Wall {
  enum class Shape { line, segment };
  Shape shape = Shape::line;
  double ax = 0.0, ay = 0.0;
  double bx = 0.0, by = 0.0;
  ContactLaw law;
};

struct WallContact {
  ContactGeometry geometry;
  WallPart part;
};

// The contact between a disk and a wall if their gap is at most `alert` (m); the wall's
// nearest point is taken at the periodic image nearest to the disk.
std::optional<WallContact> wall_contact(const Wall& wall, int body, const Disk& disk, double alert,
                                        const PeriodicBox& box);

}  // namespace cd
