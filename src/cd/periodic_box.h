// Periodic images of a 2D box, orthogonal or tilted, and how far a deforming box moves them.
#pragma once

#include <cmath>

#include "cd/kinematics.h"

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

// The most any image of a wall in `box` moves within the rest of the step: one edge vector at
// each of the box's rates at most (m).
inline double wall_image_reach(const PeriodicBox& box, const StepParameters& step)
{
  return step.advance() * (std::fabs(box.rate_x) + std::fabs(box.rate_y) + std::fabs(box.rate_xy));
}

}  // namespace cd
