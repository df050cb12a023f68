// The seam between a step and the method that finds its impulses. A step (cd/step.h) hands a
// solver its prepared contacts and the bodies' velocities with the contacts' impulses already
// applied; the solver returns with the impulses and velocities of its answer and a report.
// The settings name the method; cd::make_solver (cd/solver_registry.h) builds it. Gauss–Seidel
// (cd/gauss_seidel.h) is the core's; another is one class implementing ContactSolver and one
// cd::register_solver call, from inside the core or outside it (a bench or a test registers its
// own: the core never names it).
#pragma once

#include <string>
#include <vector>

#include "cd/contact.h"
#include "cd/convergence.h"
#include "cd/gauss_seidel_settings.h"

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
  int newton_polishes = 0;    // Newton polishes kept (cd/newton_polish.h)
  int newton_steps = 0;       // their Newton steps, kept or not

  // Adds the solve `later`, which went on from where this one stopped (a step's solves): counts
  // add up, the largest block is the larger, the norm and convergence are the later's.
  void add(const SolveReport& later);
};

// What every method reads, its name, and Gauss–Seidel's own knobs.
struct SolverSettings {
  // The fix's default: what every deck of the project uses, converged for the chute's flowing
  // layer (doc/accuracy.md); 1e-4 took the 1000-sweep cap in ordinary piles.
  double tolerance = 1.0e-3;
  int max_iterations = 1000;  // sweeps, or a method's iterations
  ConvergenceNorm norm = ConvergenceNorm::quadratic;
  std::string method = "gauss_seidel";  // a registered name (cd::make_solver)
  GaussSeidelSettings gauss_seidel{};
};

// Empty if the tolerance and the cap can run, else one line naming the keyword and its range,
// e.g. "tolerance must be in [0,1), got 2". Tolerance 0 (always the cap's iterations) is allowed
// here; a step refuses it (cd::check(StepSettings)).
std::string check_stopping(const SolverSettings& settings);

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
