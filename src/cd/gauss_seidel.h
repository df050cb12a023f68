// Moreau–Jean contact impulses by nonlinear Gauss–Seidel over contacts: sweeps of exact local
// Coulomb solves (cd/coulomb_local.h) over prepared contacts (cd/contact.h) until the
// convergence norm (cd/convergence.h) is met. The contacts' impulses, warm start included, are
// applied to the velocities before the first sweep (apply_impulses).
#pragma once

#include <string>
#include <vector>

#include "cd/contact.h"
#include "cd/convergence.h"
#include "cd/solver.h"

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
  // The stall rescue (StallRescue): a solve whose impulses moved, over stall_window sweeps, by
  // less than stall_coherence times the sum of the sweeps' changes (they went back and forth: a
  // cycle, not a slow drift), or with stall_block > 0 did so over ten windows that brought no new
  // lowest norm (a slower cycle), goes on relaxed by w = stall_relaxation and unaccelerated; each
  // further stall starts it again from zero impulses, relaxed by w once more (w^2, w^3, ..., not
  // below 0.1; stall_block below says what replaces the restarts). 0: no rescue. The defaults were chosen on the corpus of hard steps
  // (doc/stalls.md): every mu 2 cycle rescued, no mu 0.5 step touched.
  int stall_window = 100;
  double stall_coherence = 0.3;
  double stall_relaxation = 0.7;
  // How the rescue goes on after its first stall. > 0: at every stall, the contacts carrying
  // the residual and those reached through up to stall_block shared bodies (1 at the first
  // stall, one more at each next) are solved exactly (cd/block_solve.h) and the sweeps go on;
  // once stalled, a window that does not halve the norm is a stall too.
  // 0: each further stall starts the solve again from zero impulses, relaxed by w once more.
  int stall_block = 3;
  // Once a block rescue has begun, its kept block (the union of the stalls' blocks while it fits
  // cd::block_budget, which grows with the sweeps since the first stall, else the newest) is
  // solved exactly again whenever stall_block_every sweeps have passed since the last block solve:
  // at mu 2 and tolerance 1e-4 a block solved only at stalls is undone by the sweeps that follow
  // (doc/stalls_tight.md). 0: blocks at stalls only.
  int stall_block_every = 25;
};

// Empty if the settings can run, else one line naming the setting as the fix's keyword and its
// range, e.g. "relaxation must be in (0,1], got 1.5". Tolerance 0 (always the cap's sweeps) is
// allowed here; a step refuses it (cd::check(StepSettings)).
std::string check(const SolverSettings& settings);

// One sweep over the contacts [first, last) in their stored order, accumulating what
// `settings.norm` needs (of the local solves' changes). Frictionless contacts (mu = 0) take the
// shortcut of SolverSettings::frictionless_shortcut unless it is false. With conjugate
// acceleration each contact then adds `beta` times its direction (0: a plain sweep that records
// the directions).
SweepChange sweep(Contact* first, Contact* last, BodyVelocity* velocity, const SolverSettings& settings,
                  double beta = 0.0);
SweepChange sweep(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, const SolverSettings& settings,
                  double beta = 0.0);

// Watches a solve sweep by sweep: a study's hook (bench/solver_corpus), called after every full
// sweep with the report so far while the contacts and velocities hold the iterate.
class SweepObserver {
 public:
  virtual ~SweepObserver() = default;
  virtual void after_full_sweep(const SolveReport& so_far) = 0;
};

// Nonlinear Gauss–Seidel. Sweeps until the norm falls to the tolerance or the iteration cap is
// reached, in cycles of SolverSettings::full_sweep_every. `joining` is asked after the 1st,
// 2nd, 4th, 8th, ... full sweep (the step's collisions drive pairs shut in its first sweeps;
// looking after every sweep would cost a twentieth of the step) and after every converged one.
class GaussSeidel : public ContactSolver {
 public:
  // Throws std::invalid_argument with check's line if the settings cannot run.
  explicit GaussSeidel(const SolverSettings& settings);
  const SolverSettings& settings() const { return settings_; }
  void observe(SweepObserver* observer) { observer_ = observer; }
  SolveReport solve(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                    SweepExchange* exchange = nullptr, JoiningContacts* joining = nullptr) override;

  // Reused from solve to solve: once the largest problem has been seen, a solve allocates nothing.
  struct CycleWorkspace {
    std::vector<double> change_sq;  // each contact's |W dp|^2 in the cycle's full sweep
    std::vector<int> active;        // the contacts that full sweep left changing, in sweep order
    SweepChange quiet;              // the others' share of the norm's scale
  };
  // The stall tests' records: the impulses at the start of their windows (stall_window sweeps,
  // and ten times as many for cycles slower than that).
  struct StallWorkspace {
    std::vector<Local2> window_start;
    std::vector<Local2> slow_window_start;
  };

 private:
  SolveReport solve_in_full_sweeps(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                                   SweepExchange* exchange, JoiningContacts* joining);
  SolveReport solve_in_cycles(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                              SweepExchange* exchange, JoiningContacts* joining);

  SolverSettings settings_;
  CycleWorkspace cycle_;
  StallWorkspace stall_;
  SweepObserver* observer_ = nullptr;
};

// A one-off solve: GaussSeidel(settings).solve(...).
SolveReport solve_gauss_seidel(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                               const SolverSettings& settings, SweepExchange* exchange = nullptr,
                               JoiningContacts* joining = nullptr);

}  // namespace cd
