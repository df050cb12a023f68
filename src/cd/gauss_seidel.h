// Moreau–Jean contact impulses by nonlinear Gauss–Seidel over contacts: sweeps of exact local
// Coulomb solves (cd/coulomb_local.h) over prepared contacts (cd/contact.h) until the
// convergence norm (cd/convergence.h) is met. The contacts' impulses, warm start included, are
// applied to the velocities before the first sweep (apply_impulses).
#pragma once

#include <vector>

#include "cd/contact.h"
#include "cd/convergence.h"

namespace cd {

// Adds the contacts' impulses (e.g. the warm start) to the body velocities.
void apply_impulses(const std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity);

// How the sweeps are accelerated. conjugate: nonsmooth nonlinear conjugate gradients (Silcowitz,
// Niebe, Erleben 2010) with the sweep as the gradient step. After its local solve, each contact
// adds beta times its change of the previous sweep and is put back on its cone:
// beta = |W r_k|^2 / |W r_(k-1)|^2 over the contacts (r: the local solves' changes), and 0
// (a restart) when that ratio exceeds 1. The solution and the norms are those of the plain sweep.
enum class Acceleration { none, conjugate };

struct SolverSettings {
  // The fix's default: what every deck of the project uses, converged for the chute's flowing
  // layer (doc/accuracy.md); 1e-4 took the 1000-sweep cap in ordinary piles.
  double tolerance = 1.0e-3;
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

}  // namespace cd
