// The stall rescue of a Gauss–Seidel solve (cd/gauss_seidel.h): the test that tells a cycle from
// a slow drift (StallWatch) and what each stall changes (StallRescue): relaxed sweeps, restarts
// from zero impulses, exact block solves (cd/block_solve.h). The knobs are
// cd::GaussSeidelSettings's stall_*; doc/stalls.md and doc/stalls_tight.md measure them.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "cd/contact.h"
#include "cd/convergence.h"
#include "cd/gauss_seidel_settings.h"
#include "cd/solver.h"

namespace cd {

// The stall tests' records, reused from solve to solve: the impulses at the start of their
// windows (stall_window sweeps, and ten times as many for cycles slower than that).
struct StallWorkspace {
  std::vector<Local2> window_start;
  std::vector<Local2> slow_window_start;
};

// The stall test of GaussSeidelSettings::stall_window. Gauss–Seidel at high friction can cycle: a
// few contacts switch between sticking, sliding and opening from sweep to sweep, the norm sits
// on a plateau and the impulses go back and forth. A slow drift (the bed's creep mode) also
// holds the norm on a plateau, but its sweeps keep moving the impulses the same way, and
// relaxation would only slow it. The test tells them apart by the path the impulses travel:
// over a window of stall_window sweeps, the net change |W (p_end - p_start)| against the sum
// of the sweeps' changes |W dp| (both over every contact of every rank). A drift's ratio is near
// 1, a cycle's near 0: below stall_coherence the solve has stalled.
class StallWatch {
 public:
  // Windows of `window` sweeps (0: none), the impulses at their start kept in `window_start`.
  StallWatch(int window, double coherence, std::vector<Local2>& window_start, SweepExchange* exchange)
      : window_(window), coherence_(coherence), window_start_(window_start), exchange_(exchange)
  {
  }

  // Starts a window at the current impulses.
  void start(const std::vector<Contact>& contacts, int iterations);

  // Counts a sweep's change (summed over ranks). Inline, as the next: every sweep calls it.
  void add_sweep(const SweepChange& change)
  {
    if (window_ > 0) path_ += std::sqrt(change.sum_change_sq);
  }

  // True if a window ends at this sweep count (stalled() then decides on it).
  bool ends(int iterations) const { return window_ > 0 && iterations - start_ >= window_; }
  // The sweep count its window started at.
  int started() const { return start_; }

  // After a full sweep: true if the window just ended has stalled; else a new window starts
  // when one has ended.
  bool stalled(const std::vector<Contact>& contacts, int iterations);

 private:
  // Contacts that joined during the window started from a zero impulse.
  double net_change_sq(const std::vector<Contact>& contacts) const;

  int window_;
  double coherence_;
  std::vector<Local2>& window_start_;
  SweepExchange* exchange_;
  int start_ = 0;
  double path_ = 0.0;
};

// The stall rescue of one solve: its test (StallWatch) and what each stall changes. At the first
// stall the sweeps go on relaxed by w = stall_relaxation, unaccelerated. At each further stall the
// solve drops its impulses and starts again from zero, relaxed by w once more (w^2, w^3, ...,
// down to min_relaxation): in a dense flow at mu 2 the warm start can hold the iterate where no
// sweep settles, and so can a relaxation too weak for the problem, while a solve from zero,
// relaxed enough, finds a solution (doc/stalls.md).
class StallRescue {
 public:
  // A solve's rescue with `settings`, its windows starting at the contacts' impulses.
  StallRescue(const GaussSeidelSettings& settings, StallWorkspace& work, SweepExchange* exchange,
              const std::vector<Contact>& contacts);

  // The settings the next sweeps run with.
  const GaussSeidelSettings& sweeping() const { return sweeping_; }

  // Counts a sweep (summed over ranks) into the test and the report.
  void add_sweep(const SweepChange& change, SolveReport& report)
  {
    watch_.add_sweep(change);
    slow_watch_.add_sweep(change);
    report.stalled_sweeps += stalls_ > 0;
  }

  // After a full sweep that did not end the solve, once a block rescue has begun: the kept block
  // solved exactly again every GaussSeidelSettings::stall_block_every sweeps. Several ranks solve
  // theirs at once, as they do the stalls' blocks, and share the velocities they changed.
  void solve_kept_block(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report);

  // After a full sweep that did not end the solve: true if a stall was met and the sweeps change.
  bool act(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report);

 private:
  // stall_block > 0: the first stall relaxes the sweeps; every stall solves the block around the
  // residual's carriers exactly, one shared body further out each time, up to stall_block.
  // Once stalled, a window that does not halve the norm is a stall too: relaxed sweeps can drift
  // on a plateau that the coherence test no longer sees as a cycle. So is a cycle slower
  // than the window (cycles_slowly), stalled before or not.
  bool act_by_blocks(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report);

  // After a full sweep: true if a slow window (slow_windows stall windows) has just ended with
  // no new lowest norm in it and its impulses gone back and forth (the coherence test on it). A
  // cycle slower than the stall window looks coherent within it (a chute step at 1e-4: the norm
  // between 1.5e-4 and 8e-4 for 8 000 sweeps, 3 to 15 contacts switching a sweep, no stall
  // seen); a slow drift keeps its direction, and a solve that still reaches lower norms is left
  // alone.
  bool cycles_slowly(const std::vector<Contact>& contacts, const SolveReport& report);

  // The kept block: the union of the stalls' blocks while it fits the budget, else the newest.
  void keep(const std::vector<int>& block, int budget);

  void relax_unaccelerated(double relaxation);

  // The block's seeds: the contacts carrying this share of the residual, at most max_carriers of
  // them; the block as cd::block_budget allows.
  static constexpr double carried_share = 0.9;
  static constexpr int max_carriers = 16;
  // The weakest relaxation the ladder goes to: below it a sweep barely moves.
  static constexpr double min_relaxation = 0.1;
  // The slow window of cycles_slowly, in stall windows.
  static constexpr int slow_windows = 10;
  double window_residual_ = 0.0;  // the norm where the current window started (block rescue)
  // The lowest norm of the full sweeps so far, and the sweep count it was met at.
  double lowest_residual_ = std::numeric_limits<double>::infinity();
  int lowest_at_ = 0;
  std::vector<int> kept_;    // the kept block (contact indices, sorted)
  int last_kept_solve_ = 0;  // the sweep count at the last solve of a block
  StallWatch watch_;
  StallWatch slow_watch_;  // cycles_slowly's; none with stall_block 0, whose restarts do not use it
  GaussSeidelSettings sweeping_;
  SweepExchange* exchange_;
  int stalls_ = 0;
};

}  // namespace cd
