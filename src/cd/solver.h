// The seam between a step and the method that finds its impulses. A step (cd/step.h) hands a
// solver its prepared contacts and the bodies' velocities with the contacts' impulses already
// applied; the solver returns with the impulses and velocities of its answer and a report.
// Gauss–Seidel (cd/gauss_seidel.h) is the one method today; another plugs in here.
#pragma once

#include <vector>

#include "cd/contact.h"
#include "cd/convergence.h"

namespace cd {

struct SolveReport {
  int iterations = 0;            // sweeps, over every contact or over the active ones
  int solves = 1;                // solves of the step: 1, plus one each time closing pairs joined
  double contact_updates = 0.0;  // local solves over all sweeps
  double residual = 0.0;         // the stopping norm at the end
  bool converged = true;
  int stalled_sweeps = 0;     // sweeps made after a stall was detected (GaussSeidel's stall rescue)
  int cold_restarts = 0;      // times the rescue dropped the impulses and started again from zero
  int block_solves = 0;       // times the rescue solved the contacts around the residual exactly
  int largest_block = 0;      // the most contacts one of those block solves held
  int kept_block_solves = 0;  // times the rescue solved its kept block again between stalls
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
  // Sums `count` values over the ranks, in place (rarely: a solve's stall test).
  virtual void sum_over_ranks(double* values, int count) = 0;
};

// Contacts that may join a solve while it runs (cd::solve_step: pairs the iterate drives shut).
// The solve asks after each full sweep it chooses; one that converged ends only if none joined.
class JoiningContacts {
 public:
  virtual ~JoiningContacts() = default;
  // Appends to the contacts the solve runs on those that join at its current velocities, their
  // impulses zero; true if any did. `converged`: the full sweep met the tolerance (every rank
  // sees the same); the answer must then be the same on every rank: it decides whether the
  // solve ends.
  virtual bool join(bool converged) = 0;
};

class ContactSolver {
 public:
  virtual ~ContactSolver() = default;
  // Solves the contacts' impulses from their current values; `velocity` must already carry
  // them (cd::apply_impulses) and carries the answer's on return. `exchange` (optional) is called
  // as SweepExchange says; `joining` (optional) may add contacts while the solve runs.
  virtual SolveReport solve(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                            SweepExchange* exchange = nullptr, JoiningContacts* joining = nullptr) = 0;
};

}  // namespace cd
