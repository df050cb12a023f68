// Where a step meets what it does not integrate, at the grains' predicted configuration
// x_m = x_n + (1 - theta) dt v_n (cd/step.h): obstacles that a host's other integrators moved
// through the step, and the periodic images of a deforming box, which move with the box.
#pragma once

#include <cmath>

#include "cd/step.h"
#include "cd/walls.h"

namespace cd {

// An obstacle that travelled `travel` since the previous solve, seen at `now`: met at the same
// fraction of its own step as the grains, now - theta travel, so that the corrector ends it
// where it stands now.
inline Disk obstacle_at_solve(const Disk& now, const Displacement& travel, const StepParameters& step)
{
  return {now.x - step.theta * travel.dx, now.y - step.theta * travel.dy, now.radius};
}

// The step's velocity of an obstacle: its travel over the step if it moved; one nothing moved
// (travel exactly zero) keeps `own`, a surface velocity of its contacts.
inline BodyVelocity obstacle_velocity(const Displacement& travel, const BodyVelocity& own, double dt)
{
  if (travel.dx == 0.0 && travel.dy == 0.0) return own;
  return {travel.dx / dt, travel.dy / dt, own.spin};
}

// The lead of an image moving at (vx, vy) relative to its body, placed where the box stood at
// the start of the step: it reaches the step's instant lead() later.
inline Displacement image_lead(double vx, double vy, const StepParameters& step)
{
  const double lead = step.lead();
  return {lead * vx, lead * vy};
}

// How much further such an image may come within the rest of the step: advance() |v| (m).
inline double image_reach(double vx, double vy, const StepParameters& step)
{
  return step.advance() * std::sqrt(vx * vx + vy * vy);
}

// The most any image of a wall in `box` moves within the rest of the step: one edge vector at
// each of the box's rates at most (m).
inline double wall_image_reach(const PeriodicBox& box, const StepParameters& step)
{
  return step.advance() * (std::fabs(box.rate_x) + std::fabs(box.rate_y) + std::fabs(box.rate_xy));
}

// A rigid wall's pose: its displacement and its turn (rad, counter-clockwise) about a pivot, which
// it turns about first and then carries along (LAMMPS's region move and rotate).
struct WallPose {
  double dx = 0.0, dy = 0.0;  // m
  double angle = 0.0;         // rad
};

// Where a wall that went from `start` to `end` over the step stands at the grains' instant x_m:
// the same fraction of its travel, end - theta (end - start).
inline WallPose wall_at_solve(const WallPose& start, const WallPose& end, const StepParameters& step)
{
  const double back = step.theta;
  return {end.dx - back * (end.dx - start.dx), end.dy - back * (end.dy - start.dy),
          end.angle - back * (end.angle - start.angle)};
}

// That wall's rigid motion over the step (the chords of its travel), met at x_m: it turns about
// its pivot (pivot_x, pivot_y), carried by the displacement at x_m.
inline SurfaceMotion wall_motion(const WallPose& start, const WallPose& end, double pivot_x, double pivot_y,
                                 const StepParameters& step)
{
  const WallPose at_solve = wall_at_solve(start, end, step);
  return {(end.dx - start.dx) / step.dt, (end.dy - start.dy) / step.dt, (end.angle - start.angle) / step.dt,
          pivot_x + at_solve.dx, pivot_y + at_solve.dy};
}

}  // namespace cd
