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

}  // namespace cd
