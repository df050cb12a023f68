// Rigid walls of the world: infinite lines and finite segments, in a box that may be periodic.
#pragma once

#include <optional>

#include "cd/contact.h"
#include "cd/contact_geometry.h"
#include "cd/kinematics.h"
#include "cd/periodic_box.h"

namespace cd {

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
// nearest point is taken at the periodic image nearest to the disk, which moves with the box
// (ContactGeometry::image_vx, image_vy).
std::optional<WallContact> wall_contact(const Wall& wall, int body, const Disk& disk, double alert,
                                        const PeriodicBox& box);

// The rigid motion of a moving wall over one step, as the step meets it: translation at
// (vx, vy) and rotation at `spin` about `centre`, the pivot where it stands at the step's
// instant. A host that knows only the wall's poses at both ends of the step gives their chords
// (travel / dt), whose rates the step's x_m lies on.
struct SurfaceMotion {
  double vx = 0.0, vy = 0.0;              // m/s
  double spin = 0.0;                      // rad/s, counter-clockwise
  double centre_x = 0.0, centre_y = 0.0;  // m

  // Velocity of the wall's material point at (x, y) (m/s).
  void velocity_at(double x, double y, double& out_vx, double& out_vy) const
  {
    out_vx = vx - spin * (y - centre_y);
    out_vy = vy + spin * (x - centre_x);
  }
  // The largest speed of the wall within `distance` of (x, y) (m/s).
  double speed_bound(double x, double y, double distance) const;
};

// A wall's rigid motion over the step (the chords of its travel from pose `start` to `end`, cd::WallPose),
// met at x_m (cd::wall_at_solve): it turns about its pivot (pivot_x, pivot_y), carried by the
// displacement at x_m.
inline SurfaceMotion wall_motion(const WallPose& start, const WallPose& end, double pivot_x, double pivot_y,
                                 const StepParameters& step)
{
  const WallPose at_solve = wall_at_solve(start, end, step);
  return {(end.dx - start.dx) / step.dt, (end.dy - start.dy) / step.dt, (end.angle - start.angle) / step.dt,
          pivot_x + at_solve.dx, pivot_y + at_solve.dy};
}

}  // namespace cd
