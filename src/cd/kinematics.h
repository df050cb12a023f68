// The kinematics of a Moreau–Jean step, on the ground floor of the core: a body's velocity and
// inverse inertia, the step's instants, and where a step meets what it does not integrate at
// the grains' predicted configuration x_m = x_n + (1 - theta) dt v_n (obstacles that a host's
// other integrators moved through the step, images of a deforming box, moving walls).
//
//   predictor   x_m = x_n + (1 - theta) dt v_n         (predicted_motion)
//   corrector   x_{n+1} = x_m + theta dt v_{n+1}       (corrected_motion)
#pragma once

#include <cmath>

namespace cd {

// Velocity of a rigid disk in the plane.
struct BodyVelocity {
  double vx = 0.0;    // m/s
  double vy = 0.0;    // m/s
  double spin = 0.0;  // rad/s, counter-clockwise
};

// Inverse inertia of a body; zero for immobile obstacles and the world.
struct BodyInertia {
  double inv_mass = 0.0;     // 1/kg
  double inv_inertia = 0.0;  // 1/(kg m^2)
};

// A disk at the predicted configuration of the step.
struct Disk {
  double x = 0.0;
  double y = 0.0;
  double radius = 0.0;
};

struct StepParameters {
  double dt = 0.0;     // time step (s)
  double theta = 0.5;  // Moreau–Jean theta: x_{n+1} = x_n + dt((1-theta) v_n + theta v_{n+1})

  // The time from x_n to the predicted configuration x_m, where the step is solved (s).
  double lead() const { return (1.0 - theta) * dt; }
  // The time from x_m to x_{n+1}, over which v_{n+1} moves the bodies (s).
  double advance() const { return theta * dt; }
};

// Displacement of a body's centre (m).
struct Displacement {
  double dx = 0.0;
  double dy = 0.0;
};

// Predictor: the step's first displacement, to x_m = x_n + (1 - theta) dt v_n.
inline Displacement predicted_motion(const BodyVelocity& start, const StepParameters& step)
{
  const double shift = step.lead();
  return {shift * start.vx, shift * start.vy};
}

// Corrector: from x_m to x_{n+1} = x_m + theta dt v_{n+1}.
inline Displacement corrected_motion(const BodyVelocity& end, const StepParameters& step)
{
  const double advance = step.advance();
  return {advance * end.vx, advance * end.vy};
}

// The whole step's displacement, dt ((1 - theta) v_n + theta v_{n+1}).
inline Displacement step_motion(const BodyVelocity& start, const BodyVelocity& end, const StepParameters& step)
{
  const Displacement first = predicted_motion(start, step);
  const Displacement second = corrected_motion(end, step);
  return {first.dx + second.dx, first.dy + second.dy};
}

// v_n + dt (force / m, torque / I): the velocity the step would end with without contacts.
inline BodyVelocity free_velocity(const BodyVelocity& start, const BodyInertia& inertia, double fx, double fy,
                                  double torque, double dt)
{
  return {start.vx + dt * fx * inertia.inv_mass, start.vy + dt * fy * inertia.inv_mass,
          start.spin + dt * torque * inertia.inv_inertia};
}

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

}  // namespace cd
