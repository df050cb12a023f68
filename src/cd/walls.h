// Rigid walls of the world: infinite lines and finite segments, in a box that may be periodic.
#pragma once

#include <optional>

#include "cd/contact.h"
#include "cd/contact_geometry.h"

namespace cd {

// Periodic images of a 2D box, orthogonal or tilted (LAMMPS's triclinic box: edge vectors
// (length_x, 0) and (tilt_xy, length_y)), at one instant. A deforming box moves its images:
// the image shifted by (i, j) edge vectors moves at i (rate_x, 0) + j (rate_xy, rate_y)
// relative to the original (LAMMPS's h_rate; fix deform ... remap v).
struct PeriodicBox {
  bool periodic_x = false;
  bool periodic_y = false;
  double length_x = 0.0;  // m
  double length_y = 0.0;  // m
  double tilt_xy = 0.0;   // m
  double rate_x = 0.0;    // d length_x / dt (m/s)
  double rate_y = 0.0;    // d length_y / dt (m/s)
  double rate_xy = 0.0;   // d tilt_xy / dt (m/s)

  // Whole edge vectors along x and y.
  struct Shift {
    int x = 0;
    int y = 0;
  };

  // Reduces (dx, dy) to its nearest image, y first then x (exact for |tilt_xy| <= length_x / 2,
  // which LAMMPS keeps), and returns the edge vectors subtracted.
  Shift minimum_image(double& dx, double& dy) const;
  // The edge vectors that carry a point (dx, dy) from the box's lower corner into the box, as
  // LAMMPS wraps atoms that crossed a periodic side: whole cells along y, then along x measured
  // parallel to the tilted side. Zero along a direction that is not periodic.
  Shift wrapping(double dx, double dy) const;
  // Velocity of the image `shift` edge vectors away relative to the original (m/s).
  void image_velocity(const Shift& shift, double& vx, double& vy) const;
  // The box `elapsed` seconds later at its present rates.
  PeriodicBox advanced(double elapsed) const;
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

}  // namespace cd
