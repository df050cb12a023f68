// Moreau–Jean contact impulses by nonlinear Gauss–Seidel over contacts.
//
// One step, in the order the driver runs it:
//   prepare      contact frames, candidates, Delassus blocks, velocity bias of the normal law
//   warm start   apply the impulses carried over from the previous step (apply_impulses)
//   solve        sweeps of exact local Coulomb solves until the convergence norm is met
//   store        the caller keeps contact.impulse for the next step's warm start
// Restitution needs no stage of its own: Newton's law is imposed on u_n^+ + e u_n^-, so the
// pre-impact velocity enters once, as a velocity bias, when the contact is prepared.
#pragma once

#include <optional>
#include <vector>

#include "cd/contact_geometry.h"
#include "cd/convergence.h"
#include "cd/coulomb_local.h"
#include "cd/walls.h"

namespace cd {

struct StepParameters {
  double dt = 0.0;     // time step (s)
  double theta = 0.5;  // Moreau–Jean theta: x_{n+1} = x_n + dt((1-theta) v_n + theta v_{n+1})
};

// State of every body for one step. Index 0 is the world (walls): zero inverse mass and zero
// velocity, so wall contacts run through the same code as grain contacts.
struct BodySet {
  std::vector<BodyInertia> inertia;
  std::vector<BodyVelocity> start_velocity;  // v_n
  std::vector<BodyVelocity> velocity;        // free velocity before the solve, v_{n+1} after

  void reset(int body_count);  // world body included in the count
};

// One active contact, holding everything the sweep needs so that it never looks up a body.
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
  double velocity_bias = 0.0;  // b (m/s): the normal law acts on u_n + b (prepare_mechanics)
  double gap = 0.0;            // at the predicted configuration (m)
  Local2 impulse;              // accumulated over the step (N s)
  Local2 direction;            // its change in the last sweep (conjugate acceleration only)
};

// Relative velocity of a with respect to b at the contact point, in the local frame.
// Inline: the sweep calls it for every contact update.
inline Local2 relative_velocity(const Contact& c, const BodyVelocity& a, const BodyVelocity& b)
{
  const double dvx = a.vx - b.vx;
  const double dvy = a.vy - b.vy;
  return {dvx * c.normal_x + dvy * c.normal_y,
          -dvx * c.normal_y + dvy * c.normal_x - c.lever_a * a.spin - c.lever_b * b.spin};
}

// The frame of a candidate contact: bodies, normal, levers and gap; no mechanics yet.
Contact contact_frame(const ContactGeometry& geometry);

// Candidate selection: the pair is kept in the step's problem if its gap, closed at the free
// relative velocity for theta dt, is at most `alert` (m): gap + theta dt min(u_n^free, 0) <= alert.
// Pairs further apart cannot meet within the step unless other impulses drive them together
// faster than alert / (theta dt); they are watched for overlap but not solved.
bool is_candidate(const Contact& frame, const BodySet& bodies, const StepParameters& step, double alert);

// Completes a candidate: inverse masses, Delassus block, friction, and the velocity bias b of
// the normal law u_n^+ + b >= 0 ⊥ p_n >= 0:
//   impact (touching at x_m, or meeting within the step at the pre-step velocity v_n):
//       b = e min(u_n^-, 0), Newton's restitution on the pre-impact velocity u_n^-;
//   otherwise (open, and closing only through the step's forces or other impulses):
//       b = gap / (theta dt), the gap may close but not overlap by the end of the step.
// The second law holds resting contacts whose gap is a rounding error above zero, and
// keeps contacts that close gently from overlapping; it adds no restitution.
void prepare_mechanics(Contact& contact, const ContactLaw& law, const BodySet& bodies, const StepParameters& step);

// A permutation of the contacts in their order, except that contacts sharing a body are kept
// at least `spacing` places apart where a nearby contact can fill the gap: an update then never
// waits for the store of the previous update of the same body (the gain: doc/benchmarks.md).
std::vector<int> interleaved_order(const std::vector<Contact>& contacts, int body_count, int spacing = 4);

// Starts a contact from the impulse it carried at the end of the previous step. A frictionless
// contact keeps only the normal part: it can carry no tangential impulse, and the sweep never
// changes its p_t nor any spin (a carried p_t can only come from a run with another mu).
void warm_start(Contact& contact, Local2 carried);

// Adds the contacts' impulses (e.g. the warm start) to the body velocities.
void apply_impulses(const std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity);

// How the sweeps are accelerated. conjugate: nonsmooth nonlinear conjugate gradients (Silcowitz,
// Niebe, Erleben 2010) with the sweep as the gradient step. After its local solve, each contact
// adds beta times its change of the previous sweep and is put back on its cone:
// beta = |W r_k|^2 / |W r_(k-1)|^2 over the contacts (r: the local solves' changes), and 0
// (a restart) when that ratio exceeds 1. The solution and the norms are those of the plain sweep.
enum class Acceleration { none, conjugate };

struct SolverSettings {
  double tolerance = 1.0e-4;
  int max_iterations = 1000;
  double relaxation = 1.0;  // p <- w p_local + (1 - w) p_previous
  ConvergenceNorm norm = ConvergenceNorm::quadratic;
  // mu = 0 contacts solve only their normal impulse and touch no spin (solve_frictionless_local's closed form),
  // the same result as the Coulomb solver to round-off at about half the cost. false sends them
  // through the Coulomb solver: the reference the shortcut is tested and measured against.
  bool frictionless_shortcut = true;
  Acceleration acceleration = Acceleration::none;
  // Quiet contacts visited less often. A solve runs in cycles: a sweep over every contact, then
  // up to full_sweep_every - 1 sweeps over the contacts that sweep changed by more than half
  // the tolerance (|W dp| against the mean contact's |W p|), until those meet the tolerance.
  // Only a sweep over every contact ends a solve, so the answer meets the same norm as with
  // plain sweeps. Conjugate acceleration restarts with each cycle. 1: every sweep is full.
  int full_sweep_every = 1;
};

struct SolveReport {
  int iterations = 0;            // sweeps, over every contact or over the active ones
  int solves = 1;                // Gauss-Seidel solves: 1, plus one each time closing pairs joined
  double contact_updates = 0.0;  // local solves over all sweeps
  double residual = 0.0;
  bool converged = true;
};

// What a domain-decomposed run does between the sweeps of one rank: after every sweep it
// exchanges ghost velocities and reduces `change` over ranks; between solves it tells whether
// any rank wants another one. One rank needs nothing.
class SweepExchange {
 public:
  virtual ~SweepExchange() = default;
  // Every rank's copy of every body's velocity made the same (each rank's changes to its
  // copies of bodies owned elsewhere summed into the owner, then copied back): before the
  // first sweep, once the warm start is applied.
  virtual void share_velocities() = 0;
  virtual void after_sweep(SweepChange& change) = 0;
  virtual bool on_any_rank(bool here) = 0;
};

// One sweep over the contacts [first, last) in their stored order, accumulating what
// `settings.norm` needs (of the local solves' changes). Frictionless contacts (mu = 0) take the
// shortcut of SolverSettings::frictionless_shortcut unless it is false. With conjugate
// acceleration each contact then adds `beta` times its direction (0: a plain sweep that records
// the directions).
SweepChange sweep(Contact* first, Contact* last, BodyVelocity* velocity, const SolverSettings& settings,
                  double beta = 0.0);
SweepChange sweep(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, const SolverSettings& settings,
                  double beta = 0.0);

// Contacts that may join a solve while it runs (cd::solve_step: pairs the iterate drives shut).
// The solve asks after each full sweep; one that converged ends only if none joined.
class JoiningContacts {
 public:
  virtual ~JoiningContacts() = default;
  // Appends to the contacts the solve runs on those that join at its current velocities, their
  // impulses zero; true if any did. `converged`: the full sweep met the tolerance (every rank
  // sees the same); the answer must then be the same on every rank: it decides whether the
  // solve ends.
  virtual bool join(bool converged) = 0;
};

// Sweeps until the norm falls to the tolerance or the iteration cap is reached, in cycles of
// SolverSettings::full_sweep_every. The contacts' impulses must already be applied to
// `velocity` (apply_impulses). `joining` (optional) is asked after the 1st, 2nd, 4th, 8th, ...
// full sweep (the step's collisions drive pairs shut in its first sweeps; looking after every
// sweep would cost a twentieth of the step) and after every converged one.
SolveReport solve_gauss_seidel(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                               const SolverSettings& settings, SweepExchange* exchange = nullptr,
                               JoiningContacts* joining = nullptr);

// u_n of a pair not (yet) solved: relative_velocity(contact_frame(pair), ...).n.
inline double normal_velocity(const ContactGeometry& pair, const std::vector<BodyVelocity>& velocity)
{
  const BodyVelocity& a = velocity[pair.body_a];
  const BodyVelocity& b = velocity[pair.body_b];
  return (a.vx - b.vx) * pair.normal_x + (a.vy - b.vy) * pair.normal_y;
}

// Linearised gap at the end of the step: gap + theta dt u_n^+ (m).
inline double end_of_step_gap(double gap, double normal_velocity, const StepParameters& step)
{
  return gap + step.theta * step.dt * normal_velocity;
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
