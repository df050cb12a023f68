// The contacts of a step and their mechanics: the bodies a step moves, the law of a pair, a
// contact's frame and Delassus block, the candidates, the velocity bias of the normal law and the
// warm start. What the sweeps solve (cd/gauss_seidel.h) and what a step collects (cd/detection.h)
// are made of these.
//
// Restitution needs no stage of its own: Newton's law is imposed on u_n^+ + e u_n^-, so the
// pre-impact velocity enters once, as a velocity bias, when the contact is prepared.
#pragma once

#include <vector>

#include "cd/contact_geometry.h"
#include "cd/coulomb_local.h"

namespace cd {

// Friction and restitution of one kind of contact.
struct ContactLaw {
  double mu = 0.0;           // Coulomb coefficient (one value, no static/dynamic split)
  double restitution = 0.0;  // Newton normal restitution e in [0, 1]
};

// State of every body for one step. Index 0 is the world (walls): zero inverse mass and zero
// velocity, so wall contacts run through the same code as grain contacts.
struct BodySet {
  std::vector<BodyInertia> inertia;
  std::vector<BodyVelocity> start_velocity;  // v_n
  std::vector<BodyVelocity> velocity;        // free velocity before the solve, v_{n+1} after

  void reset(int body_count);  // world body included in the count
};

// One active contact, holding everything the sweep needs so that it never looks up a body, and
// nothing else: its gap and its key are the step's (StepContacts), read after the solve.
struct Contact {
  int body_a = 0;
  int body_b = 0;
  double normal_x = 0.0;  // unit normal from b to a; tangent t = (-n_y, n_x)
  double normal_y = 0.0;
  double lever_a = 0.0;  // centre-to-contact distances (m)
  double lever_b = 0.0;
  double inv_mass_a = 0.0;  // 1/kg
  double inv_mass_b = 0.0;
  double spin_gain_a = 0.0;  // lever * inverse inertia: spin change per tangential impulse
  double spin_gain_b = 0.0;
  DiskDelassus delassus;  // local W, diagonal for disks
  double mu = 0.0;
  // b (m/s): the contact law acts on u + b (law_velocity). Its normal part is the normal law's
  // (prepare_mechanics); both parts take off the velocity of b's image relative to body b, which
  // is not zero only across the sides of a deforming box (ContactGeometry::image_vx, image_vy).
  Local2 velocity_bias;
  Local2 impulse;    // accumulated over the step (N s)
  Local2 direction;  // its change in the last sweep (conjugate acceleration only)
};

// Relative velocity of body a with respect to body b at the contact point, in the local frame.
// Inline: the sweep calls it for every contact update.
inline Local2 relative_velocity(const Contact& c, const BodyVelocity& a, const BodyVelocity& b)
{
  const double dvx = a.vx - b.vx;
  const double dvy = a.vy - b.vy;
  return {dvx * c.normal_x + dvy * c.normal_y,
          -dvx * c.normal_y + dvy * c.normal_x - c.lever_a * a.spin - c.lever_b * b.spin};
}

// The velocity the contact's law acts on: u + b (Contact::velocity_bias).
inline Local2 law_velocity(const Contact& c, const BodyVelocity& a, const BodyVelocity& b)
{
  const Local2 u = relative_velocity(c, a, b);
  return {u.n + c.velocity_bias.n, u.t + c.velocity_bias.t};
}

// The contact point (midway across `gap`) of a contact whose body a is the disk centred at
// (a_x, a_y) at the predicted configuration.
struct Point {
  double x = 0.0;  // m
  double y = 0.0;
};
inline Point contact_point(const Contact& c, double gap, double a_x, double a_y)
{
  const double to_point = c.lever_a + 0.5 * gap;
  return {a_x - to_point * c.normal_x, a_y - to_point * c.normal_y};
}

// An impulse of the contact's local frame (p_n along n, p_t along t = (-n_y, n_x)) in world
// components: what it gives body a (body b gets the opposite).
struct WorldImpulse {
  double x = 0.0;  // N s
  double y = 0.0;
};
inline WorldImpulse world_impulse(const Contact& c, Local2 p)
{
  return {p.n * c.normal_x - p.t * c.normal_y, p.n * c.normal_y + p.t * c.normal_x};
}

// Adds the impulse dp (on a; -dp on b) to both bodies. A tangential impulse spins both disks
// the same way: its lever arms are -r_a n on a and +r_b n on b, with opposite forces. Always
// inlined: the sweep's inner loop calls it, and GCC left it a call once the sweep had eight kinds
// (the 45 d chute 1.3 times slower).
[[gnu::always_inline]] inline void apply_impulse(const Contact& c, Local2 dp, BodyVelocity& a, BodyVelocity& b)
{
  const WorldImpulse p = world_impulse(c, dp);
  a.vx += c.inv_mass_a * p.x;
  a.vy += c.inv_mass_a * p.y;
  a.spin -= c.spin_gain_a * dp.t;
  b.vx -= c.inv_mass_b * p.x;
  b.vy -= c.inv_mass_b * p.y;
  b.spin -= c.spin_gain_b * dp.t;
}

// What the local impulse dp on contact c alone gives `body` (zero if it is neither of c's): with
// relative_velocity, a column of the contacts' Delassus operator.
inline BodyVelocity impulse_response(const Contact& c, Local2 dp, int body)
{
  BodyVelocity a{}, b{};
  apply_impulse(c, dp, a, b);
  if (body == c.body_a) return a;
  if (body == c.body_b) return b;
  return {};
}

// Adds the contacts' impulses (e.g. the warm start) to the body velocities: what a step does
// before its solver's first sweep.
void apply_impulses(const std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity);

// The frame of a candidate contact: bodies, normal, levers and gap; no mechanics yet.
Contact contact_frame(const ContactGeometry& geometry);

// Candidate selection: the pair is kept in the step's problem if its gap, closed at the free
// relative velocity for theta dt, is at most `alert` (m): gap + theta dt min(u_n^free, 0) <= alert.
// Pairs further apart cannot meet within the step unless other impulses drive them together
// faster than alert / (theta dt); they are watched for overlap but not solved.
bool is_candidate(const Contact& frame, double gap, const BodySet& bodies, const StepParameters& step, double alert);

// Completes a candidate, once per frame (it adds to the frame's bias): inverse masses, Delassus
// block, friction, and the velocity bias b of the normal law u_n^+ + b >= 0 ⊥ p_n >= 0:
//   impact (touching at x_m, or meeting within the step at the pre-step velocity v_n):
//       b = e min(u_n^-, 0), Newton's restitution on the pre-impact velocity u_n^-;
//   otherwise (open, and closing only through the step's forces or other impulses):
//       b = gap / (theta dt), the gap may close but not overlap by the end of the step.
// The second law holds resting contacts whose gap is a rounding error above zero, and
// keeps contacts that close gently from overlapping; it adds no restitution.
void prepare_mechanics(Contact& contact, double gap, const ContactLaw& law, const BodySet& bodies,
                       const StepParameters& step);

// contact_frame, then prepare_mechanics at the geometry's gap.
Contact prepared_contact(const ContactGeometry& geometry, const ContactLaw& law, const BodySet& bodies,
                         const StepParameters& step);

// Starts a contact from the impulse it carried at the end of the previous step. A frictionless
// contact keeps only the normal part: it can carry no tangential impulse, and the sweep never
// changes its p_t nor any spin (a carried p_t can only come from a run with another mu).
void warm_start(Contact& contact, Local2 carried);

// u_n of a pair not (yet) solved: relative_velocity(contact_frame(pair), ...).n.
inline double normal_velocity(const ContactGeometry& pair, const std::vector<BodyVelocity>& velocity)
{
  const BodyVelocity& a = velocity[pair.body_a];
  const BodyVelocity& b = velocity[pair.body_b];
  return (a.vx - b.vx - pair.image_vx) * pair.normal_x + (a.vy - b.vy - pair.image_vy) * pair.normal_y;
}

// Linearised gap at the end of the step: gap + theta dt u_n^+ (m).
inline double end_of_step_gap(double gap, double normal_velocity, const StepParameters& step)
{
  return gap + step.advance() * normal_velocity;
}

// True if a pair left out of the solve would overlap at the end of the step with the solved
// velocities: other impulses (a grain stopped by the floor, say) drove it shut faster than
// the candidate selection foresaw. Such pairs join the contacts and the solve continues.
// Inline: a solve asks it of every watched pair several times.
inline bool closes_after_solve(const ContactGeometry& pair, const std::vector<BodyVelocity>& velocity,
                               const StepParameters& step)
{
  return end_of_step_gap(pair.gap, normal_velocity(pair, velocity), step) < 0.0;
}

}  // namespace cd
