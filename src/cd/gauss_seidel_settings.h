// Gauss–Seidel's own knobs (cd/gauss_seidel.h): relaxation, acceleration, cycles over the
// changing contacts and the stall rescue (cd/stall_rescue.h). What every method reads, the
// tolerance, the sweep cap and the norm, is cd::SolverSettings's (cd/solver.h).
#pragma once

#include <string>

namespace cd {

// How the sweeps are accelerated. conjugate: nonsmooth nonlinear conjugate gradients (Silcowitz,
// Niebe, Erleben 2010) with the sweep as the gradient step. After its local solve, each contact
// adds beta times its change of the previous sweep and is put back on its cone:
// beta = |W r_k|^2 / |W r_(k-1)|^2 over the contacts (r: the local solves' changes), and 0
// (a restart) when that ratio exceeds 1. The solution and the norms are those of the plain sweep.
enum class Acceleration { none, conjugate };

struct GaussSeidelSettings {
  double relaxation = 1.0;  // p <- w p_local + (1 - w) p_previous
  // Over-relaxation w in [1, 2) of the sweeps once a full sweep changed no contact's law face
  // (open, sliding either way, sticking): p <- w p_local + (1 - w) p_previous put back on its
  // cone, until a sweep changes a face again; never while the stall rescue relaxes. On the faces
  // the local solves are linear and successive over-relaxation speeds Gauss–Seidel where they are
  // ill-conditioned (the resting pile at 1e-6: doc/peers.md). 1: off, the faces not even counted.
  double over_relaxation = 1.0;
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
  // The Newton polish (cd/newton_polish.h): once a full sweep's norm is within ten times the
  // tolerance, semismooth Newton steps on every contact, kept where they lower the residual.
  bool newton_polish = false;
};

// Empty if the knobs can run, else one line naming the knob as the fix's keyword and its
// range, e.g. "relaxation must be in (0,1], got 1.5".
std::string check(const GaussSeidelSettings& settings);

}  // namespace cd
