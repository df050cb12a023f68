// The Gauss–Seidel sweeps over prepared contacts and the solves made of them (cd/gauss_seidel.h).
#include "cd/gauss_seidel.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include "cd/block_solve.h"
#include "cd/refusal.h"

namespace cd {

namespace {

// The normal part of apply_impulse alone: what a frictionless contact applies. It reads and
// writes no spin.
inline void apply_normal_impulse(const Contact& c, double dp_n, BodyVelocity& a, BodyVelocity& b)
{
  const double px = dp_n * c.normal_x;
  const double py = dp_n * c.normal_y;
  a.vx += c.inv_mass_a * px;
  a.vy += c.inv_mass_a * py;
  b.vx -= c.inv_mass_b * px;
  b.vy -= c.inv_mass_b * py;
}

// What a sweep accumulates for its norm: the quadratic norm needs no square root.
template <ConvergenceNorm norm>
inline void record_change(SweepChange& change, Local2 velocity_change, Local2 velocity_scale)
{
  if constexpr (norm == ConvergenceNorm::quadratic) change.add_squares(velocity_change, velocity_scale);
  else change.add(velocity_change, velocity_scale);
}

// The impulse p (every other impulse frozen) or, under relaxation w, w p + (1 - w) p_previous.
inline Local2 relaxed(Local2 p, Local2 previous, double relaxation)
{
  if (relaxation == 1.0) return p;
  return {relaxation * p.n + (1.0 - relaxation) * previous.n, relaxation * p.t + (1.0 - relaxation) * previous.t};
}

// Conjugate acceleration of one contact's new impulse p: p + beta d back on the cone, and that
// step's change becomes the direction of the next sweep.
template <bool conjugate>
inline Local2 accelerated(Contact& c, Local2 p, double beta)
{
  if constexpr (!conjugate) return p;
  const Local2 pushed = solve_coulomb_disk({p.n + beta * c.direction.n, p.t + beta * c.direction.t}, c.mu);
  c.direction = {pushed.n - c.impulse.n, pushed.t - c.impulse.t};
  return pushed;
}

// law_velocity, whose tangential bias is not zero only where an image slides across a deforming
// box's side: without such images (sliding_images false) the sweep leaves that add off the
// local solve's dependency chain, which cost ordinary boxes 3 % of the sweep.
template <bool sliding_images>
inline Local2 swept_law_velocity(const Contact& c, const BodyVelocity& a, const BodyVelocity& b)
{
  if constexpr (sliding_images) return law_velocity(c, a, b);
  const Local2 u = relative_velocity(c, a, b);
  return {u.n + c.velocity_bias.n, u.t};
}

// Exact local solve of one contact with every other impulse frozen, in the accumulated-impulse
// form: the impulse that would stop the contact is the current one minus W^-1 (u + b), with u
// the relative velocity that already includes the contact's own impulse. The norm records the
// local solve's change, before any acceleration.
template <ConvergenceNorm norm, bool conjugate, bool sliding_images>
[[gnu::always_inline]] inline double update_frictional(Contact& c, BodyVelocity* velocity, double relaxation,
                                                       double beta, SweepChange& change)
{
  BodyVelocity& a = velocity[c.body_a];
  BodyVelocity& b = velocity[c.body_b];
  const Local2 u = swept_law_velocity<sliding_images>(c, a, b);
  const Local2 stick{c.impulse.n - c.delassus.inverse_nn * u.n, c.impulse.t - c.delassus.inverse_tt * u.t};
  const Local2 local = solve_coulomb_disk(stick, c.mu);
  const Local2 solved = relaxed(local, c.impulse, relaxation);
  // The norm takes the plain local solve's change, which relaxation would shrink by w: a relaxed
  // solve then stops where a plain sweep would change no more than the tolerance allows.
  const Local2 velocity_change = c.delassus.times({local.n - c.impulse.n, local.t - c.impulse.t});
  record_change<norm>(change, velocity_change, c.delassus.times(solved));
  const Local2 p = accelerated<conjugate>(c, solved, beta);
  const Local2 dp{p.n - c.impulse.n, p.t - c.impulse.t};
  c.impulse = p;
  apply_impulse(c, dp, a, b);
  return velocity_change.n * velocity_change.n + velocity_change.t * velocity_change.t;
}

// update_frictional for mu = 0, where p_t stays 0 (warm_start drops a carried one): the
// normal velocity and the normal impulse; no tangential solve, no spin.
template <ConvergenceNorm norm, bool conjugate>
[[gnu::always_inline]] inline double update_frictionless(Contact& c, BodyVelocity* velocity, double relaxation,
                                                         double beta, SweepChange& change)
{
  BodyVelocity& a = velocity[c.body_a];
  BodyVelocity& b = velocity[c.body_b];
  const double stick_n = c.impulse.n - c.delassus.inverse_nn * law_velocity(c, a, b).n;
  const double local_n = std::max(stick_n, 0.0);
  const double solved_n = relaxed({local_n, 0.0}, c.impulse, relaxation).n;
  const double velocity_change = c.delassus.nn * (local_n - c.impulse.n);
  record_change<norm>(change, {velocity_change, 0.0}, {c.delassus.nn * solved_n, 0.0});
  const double p_n = accelerated<conjugate>(c, {solved_n, 0.0}, beta).n;
  const double dp_n = p_n - c.impulse.n;
  c.impulse.n = p_n;
  apply_normal_impulse(c, dp_n, a, b);
  return velocity_change * velocity_change;
}

}  // namespace

void apply_impulses(const std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity)
{
  for (const Contact& c : contacts) apply_impulse(c, c.impulse, velocity[c.body_a], velocity[c.body_b]);
}

namespace {

// The local solve of one contact, its kind chosen per contact: a branch per contact rather
// than one sweep per kind serves scenes that mix mu = 0 with friction (mu/types, rough walls).
// Returns |W dp|^2 of the local solve.
template <class Kind>
[[gnu::always_inline]] inline double update_contact(Contact& c, BodyVelocity* velocity, bool shortcut,
                                                    double relaxation, double beta, SweepChange& change)
{
  if (shortcut && c.mu == 0.0)
    return update_frictionless<Kind::norm, Kind::conjugate>(c, velocity, relaxation, beta, change);
  return update_frictional<Kind::norm, Kind::conjugate, Kind::sliding_images>(c, velocity, relaxation, beta, change);
}

template <ConvergenceNorm norm_, bool conjugate_, bool sliding_images_>
struct SweepKind {
  static constexpr ConvergenceNorm norm = norm_;
  static constexpr bool conjugate = conjugate_;
  static constexpr bool sliding_images = sliding_images_;
};

template <bool sliding_images, class Loop>
SweepChange for_kind(const SolverSettings& settings, Loop loop)
{
  const bool quadratic = settings.norm == ConvergenceNorm::quadratic;
  if (settings.acceleration == Acceleration::conjugate)
    return quadratic ? loop(SweepKind<ConvergenceNorm::quadratic, true, sliding_images>{})
                     : loop(SweepKind<ConvergenceNorm::maximum, true, sliding_images>{});
  return quadratic ? loop(SweepKind<ConvergenceNorm::quadratic, false, sliding_images>{})
                   : loop(SweepKind<ConvergenceNorm::maximum, false, sliding_images>{});
}

// Calls loop(SweepKind<norm, conjugate, sliding_images>{}) for the settings' norm and
// acceleration and the contacts' images, so that the sweep loops are compiled once per kind.
// The loops copy the settings they read into locals: a store to a velocity could otherwise
// alias them and force a reload per contact.
template <class Loop>
SweepChange for_kind(const SolverSettings& settings, bool sliding_images, Loop loop)
{
  return sliding_images ? for_kind<true>(settings, loop) : for_kind<false>(settings, loop);
}

// A sweep over [first, last); with `change_sq`, each contact's |W dp|^2 lands in it.
SweepChange sweep_measuring(Contact* first, Contact* last, BodyVelocity* velocity, const SolverSettings& settings,
                            bool sliding_images, double beta, double* change_sq)
{
  return for_kind(settings, sliding_images, [&](auto kind) {
    using Kind = decltype(kind);
    const bool shortcut = settings.frictionless_shortcut;
    const double w = settings.relaxation;
    SweepChange change;
    for (Contact* c = first; c != last; ++c) {
      const double changed = update_contact<Kind>(*c, velocity, shortcut, w, beta, change);
      if (change_sq) change_sq[c - first] = changed;
    }
    return change;
  });
}

// A sweep over the listed contacts, in the list's order.
SweepChange sweep_listed(Contact* contacts, const std::vector<int>& listed, BodyVelocity* velocity,
                         const SolverSettings& settings, bool sliding_images, double beta)
{
  return for_kind(settings, sliding_images, [&](auto kind) {
    using Kind = decltype(kind);
    const bool shortcut = settings.frictionless_shortcut;
    const double w = settings.relaxation;
    SweepChange change;
    for (const int k : listed) update_contact<Kind>(contacts[k], velocity, shortcut, w, beta, change);
    return change;
  });
}

// True if some contact's law velocity has a tangential bias (an image sliding across the side
// of a deforming box).
bool has_sliding_images(const Contact* first, const Contact* last)
{
  return std::any_of(first, last, [](const Contact& c) { return c.velocity_bias.t != 0.0; });
}

bool has_sliding_images(const std::vector<Contact>& contacts)
{
  return has_sliding_images(contacts.data(), contacts.data() + contacts.size());
}

}  // namespace

SweepChange sweep(Contact* first, Contact* last, BodyVelocity* velocity, const SolverSettings& settings, double beta)
{
  return sweep_measuring(first, last, velocity, settings, has_sliding_images(first, last), beta, nullptr);
}

SweepChange sweep(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, const SolverSettings& settings,
                  double beta)
{
  return sweep(contacts.data(), contacts.data() + contacts.size(), velocity.data(), settings, beta);
}

namespace {

// The beta of conjugate acceleration, sweep after sweep of one solve. beta = |W r_k|^2 /
// |W r_(k-1)|^2, summed over the contacts of every rank, and 0 (a restart) after the first
// sweep or when the change grew. Where pushes keep failing (a nearly converged solve, whose
// slow plain progress the pushes only disturb), or when half the cap is spent, the solve goes
// on with plain sweeps: three pushed sweeps in a row that raised the change switch it off.
class ConjugateBeta {
 public:
  double next(double change_sq, int iterations, int max_iterations)
  {
    if (beta_ > 0.0) failures_ = change_sq > previous_sq_ ? failures_ + 1 : 0;
    const bool restart = !(previous_sq_ > 0.0) || change_sq > previous_sq_;
    const bool give_up = off_for_the_solve_ || failures_ >= max_failures || iterations >= max_iterations / 2;
    beta_ = restart || give_up ? 0.0 : change_sq / previous_sq_;
    previous_sq_ = change_sq;
    return beta_;
  }

  // Starts the directions afresh for a new cycle of SolverSettings::full_sweep_every, in
  // which acceleration may switch itself off again; a cycle that ended no closer to the
  // solution than the one before (its full sweep changed as much) switches it off for the rest
  // of the solve: at a tolerance near round-off the pushes only disturb.
  void restart(bool cycle_progressed)
  {
    beta_ = 0.0;
    previous_sq_ = 0.0;
    failures_ = 0;
    off_for_the_solve_ = off_for_the_solve_ || !cycle_progressed;
  }

 private:
  static constexpr int max_failures = 3;
  bool off_for_the_solve_ = false;
  double beta_ = 0.0;
  double previous_sq_ = 0.0;
  int failures_ = 0;
};

// Whether a solve asks for joining contacts after its full_sweeps-th full sweep.
bool looks_for_joining(int full_sweeps, bool converged)
{
  return converged || (full_sweeps & (full_sweeps - 1)) == 0;
}

// Counts one sweep of `updates` local solves into the report; true if it met the tolerance.
bool count_sweep(SolveReport& report, const SweepChange& change, std::size_t updates, const SolverSettings& settings)
{
  ++report.iterations;
  report.contact_updates += static_cast<double>(updates);
  report.residual = change.residual(settings.norm);
  return report.residual <= settings.tolerance;
}

// The stall test of SolverSettings::stall_window. Gauss–Seidel at high friction can cycle: a
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
  void start(const std::vector<Contact>& contacts, int iterations)
  {
    if (window_ == 0) return;
    window_start_.resize(contacts.size());
    for (std::size_t k = 0; k < contacts.size(); k++) window_start_[k] = contacts[k].impulse;
    start_ = iterations;
    path_ = 0.0;
  }

  // Counts a sweep's change (summed over ranks).
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
  bool stalled(const std::vector<Contact>& contacts, int iterations)
  {
    if (window_ == 0 || iterations - start_ < window_) return false;
    double sums[2] = {net_change_sq(contacts), path_};
    if (exchange_) exchange_->sum_over_ranks(sums, 2);
    if (std::sqrt(sums[0]) < coherence_ * sums[1]) return true;
    start(contacts, iterations);
    return false;
  }

 private:
  // Contacts that joined during the window started from a zero impulse.
  double net_change_sq(const std::vector<Contact>& contacts) const
  {
    double sum = 0.0;
    for (std::size_t k = 0; k < contacts.size(); k++) {
      const Local2 before = k < window_start_.size() ? window_start_[k] : Local2{};
      const Local2 moved =
          contacts[k].delassus.times({contacts[k].impulse.n - before.n, contacts[k].impulse.t - before.t});
      sum += moved.n * moved.n + moved.t * moved.t;
    }
    return sum;
  }

  int window_;
  double coherence_;
  std::vector<Local2>& window_start_;
  SweepExchange* exchange_;
  int start_ = 0;
  double path_ = 0.0;
};

// The impulses taken off the velocities and set to zero: a solve starting again from nothing.
void remove_impulses(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity)
{
  for (Contact& c : contacts) {
    apply_impulse(c, {-c.impulse.n, -c.impulse.t}, velocity[c.body_a], velocity[c.body_b]);
    c.impulse = {};
    c.direction = {};
  }
}

// The stall rescue of one solve: its test (StallWatch) and what each stall changes. At the first
// stall the sweeps go on relaxed by w = stall_relaxation, unaccelerated. At each further stall the
// solve drops its impulses and starts again from zero, relaxed by w once more (w^2, w^3, ...,
// down to min_relaxation): in a dense flow at mu 2 the warm start can hold the iterate where no
// sweep settles, and so can a relaxation too weak for the problem, while a solve from zero,
// relaxed enough, finds a solution (doc/stalls.md).
class StallRescue {
 public:
  StallRescue(const SolverSettings& settings, GaussSeidel::StallWorkspace& work, SweepExchange* exchange,
              const std::vector<Contact>& contacts)
      : watch_(settings.stall_window, settings.stall_coherence, work.window_start, exchange),
        slow_watch_(settings.stall_block > 0 ? slow_windows * settings.stall_window : 0, settings.stall_coherence,
                    work.slow_window_start, exchange),
        sweeping_(settings),
        exchange_(exchange)
  {
    watch_.start(contacts, 0);
    slow_watch_.start(contacts, 0);
  }

  // The settings the next sweeps run with.
  const SolverSettings& sweeping() const { return sweeping_; }

  // Counts a sweep (summed over ranks) into the test and the report.
  void add_sweep(const SweepChange& change, SolveReport& report)
  {
    watch_.add_sweep(change);
    slow_watch_.add_sweep(change);
    report.stalled_sweeps += stalls_ > 0;
  }

  // After a full sweep that did not end the solve, once a block rescue has begun: the kept block
  // solved exactly again every SolverSettings::stall_block_every sweeps. Several ranks solve
  // theirs at once, as they do the stalls' blocks, and share the velocities they changed.
  void solve_kept_block(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report)
  {
    const int every = sweeping_.stall_block_every;
    // The same on every rank: the sweep count and the block solves are.
    if (report.block_solves == 0 || every == 0 || report.iterations - last_kept_solve_ < every) return;
    last_kept_solve_ = report.iterations;
    if (!kept_.empty()) {
      solve_block(contacts, velocity, kept_);
      ++report.kept_block_solves;
    }
    if (exchange_) exchange_->share_velocities();
  }

  // After a full sweep that did not end the solve: true if a stall was met and the sweeps change.
  bool act(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report)
  {
    if (sweeping_.stall_block > 0) return act_by_blocks(contacts, velocity, report);
    const double relaxation = sweeping_.relaxation * sweeping_.stall_relaxation;
    if (relaxation < min_relaxation || !watch_.stalled(contacts, report.iterations)) return false;
    if (stalls_ > 0) {
      remove_impulses(contacts, velocity);
      if (exchange_) exchange_->share_velocities();
      ++report.cold_restarts;
    }
    ++stalls_;
    relax_unaccelerated(relaxation);
    watch_.start(contacts, report.iterations);
    return true;
  }

 private:
  // stall_block > 0: the first stall relaxes the sweeps; every stall solves the block around the
  // residual's carriers exactly, one shared body further out each time, up to stall_block.
  // Once stalled, a window that does not halve the norm is a stall too: relaxed sweeps can drift
  // on a plateau that the coherence test no longer sees as a cycle. So is a cycle slower
  // than the window (cycles_slowly), stalled before or not.
  bool act_by_blocks(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report)
  {
    const bool window_ends = watch_.ends(report.iterations);
    bool stalled = watch_.stalled(contacts, report.iterations);
    if (window_ends && stalls_ > 0 && !(report.residual <= 0.5 * window_residual_)) stalled = true;
    if (window_ends) window_residual_ = report.residual;
    if (cycles_slowly(contacts, report)) stalled = true;
    if (!stalled) return false;
    if (++stalls_ == 1) relax_unaccelerated(sweeping_.relaxation * sweeping_.stall_relaxation);
    const int hops = std::min(stalls_, sweeping_.stall_block);
    const std::vector<int> seeds = residual_carriers(contacts, velocity, carried_share, max_carriers);
    // The budget grows with the sweeps spent since the first stall: a trap that outlasts small
    // blocks gets larger ones, their cost still within the sweeps' (cd::block_budget).
    const int budget = block_budget(sweeping_.stall_window + report.stalled_sweeps, contacts.size(), max_carriers);
    const std::vector<int> block = block_around(contacts, static_cast<int>(velocity.size()), seeds, hops, budget);
    keep(block, budget);
    solve_block(contacts, velocity, block);
    if (exchange_) exchange_->share_velocities();
    ++report.block_solves;
    report.largest_block = std::max(report.largest_block, static_cast<int>(block.size()));
    last_kept_solve_ = report.iterations;
    watch_.start(contacts, report.iterations);
    slow_watch_.start(contacts, report.iterations);
    return true;
  }

  // After a full sweep: true if a slow window (slow_windows stall windows) has just ended with
  // no new lowest norm in it and its impulses gone back and forth (the coherence test on it). A
  // cycle slower than the stall window looks coherent within it (a chute step at 1e-4: the norm
  // between 1.5e-4 and 8e-4 for 8 000 sweeps, 3 to 15 contacts switching a sweep, no stall
  // seen); a slow drift keeps its direction, and a solve that still reaches lower norms is left
  // alone.
  bool cycles_slowly(const std::vector<Contact>& contacts, const SolveReport& report)
  {
    if (!(report.residual >= lowest_residual_)) lowest_residual_ = report.residual, lowest_at_ = report.iterations;
    if (!slow_watch_.ends(report.iterations)) return false;
    const bool progressed = lowest_at_ > slow_watch_.started();
    const bool went_back_and_forth = slow_watch_.stalled(contacts, report.iterations);
    if (went_back_and_forth && progressed) slow_watch_.start(contacts, report.iterations);
    return went_back_and_forth && !progressed;
  }

  // The kept block: the union of the stalls' blocks while it fits the budget, else the newest.
  void keep(const std::vector<int>& block, int budget)
  {
    std::vector<int> joined;
    std::set_union(kept_.begin(), kept_.end(), block.begin(), block.end(), std::back_inserter(joined));
    kept_ = static_cast<int>(joined.size()) <= budget ? std::move(joined) : block;
  }

  void relax_unaccelerated(double relaxation)
  {
    sweeping_.relaxation = relaxation;
    sweeping_.acceleration = Acceleration::none;
  }

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
  SolverSettings sweeping_;
  SweepExchange* exchange_;
  int stalls_ = 0;
};

// The contacts a cycle's full sweep left changing, by their place in the contact list (in
// sweep order). The quiet ones keep their impulses until the next full sweep, so their share of
// the norm's scale is summed once.
void select_active(GaussSeidel::CycleWorkspace& work, const std::vector<Contact>& contacts, double quiet_sq)
{
  work.active.clear();
  work.quiet = SweepChange{};
  for (std::size_t k = 0; k < contacts.size(); k++) {
    if (work.change_sq[k] > quiet_sq) work.active.push_back(static_cast<int>(k));
    else work.quiet.add({0.0, 0.0}, contacts[k].delassus.times(contacts[k].impulse));
  }
}

// A sweep over the active contacts, its sums completed by the quiet contacts' scale.
SweepChange sweep_active(const GaussSeidel::CycleWorkspace& work, std::vector<Contact>& contacts,
                         BodyVelocity* velocity, const SolverSettings& settings, bool sliding_images, double beta)
{
  SweepChange change = sweep_listed(contacts.data(), work.active, velocity, settings, sliding_images, beta);
  change.merge(work.quiet);
  return change;
}

// A contact counts as quiet when its change in the full sweep is below this fraction of the
// tolerance (SweepChange::quiet_change_sq). Measured on the 45 d chute (doc/benchmarks.md):
// 0.25–1 cut the local solves alike; 3 left more for the full sweeps to find.
constexpr double quiet_fraction = 0.5;

}  // namespace

// Every sweep over every contact (full_sweep_every 1).
SolveReport GaussSeidel::solve_in_full_sweeps(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                                              SweepExchange* exchange, JoiningContacts* joining)
{
  SolveReport report;
  ConjugateBeta conjugate;
  StallRescue rescue(settings_, stall_, exchange, contacts);
  bool sliding_images = has_sliding_images(contacts);
  double beta = 0.0;
  while (report.iterations < settings_.max_iterations) {
    SweepChange change = sweep_measuring(contacts.data(), contacts.data() + contacts.size(), velocity.data(),
                                         rescue.sweeping(), sliding_images, beta, nullptr);
    if (exchange) exchange->after_sweep(change);
    const bool converged = count_sweep(report, change, contacts.size(), settings_);
    rescue.add_sweep(change, report);
    if (observer_) observer_->after_full_sweep(report);
    const bool joined = joining && looks_for_joining(report.iterations, converged) && joining->join(converged);
    if (joined) sliding_images = has_sliding_images(contacts);
    if (converged && !joined) return report;
    rescue.solve_kept_block(contacts, velocity, report);
    if (rescue.act(contacts, velocity, report)) beta = 0.0;
    else if (rescue.sweeping().acceleration == Acceleration::conjugate)
      beta = conjugate.next(change.sum_change_sq, report.iterations, settings_.max_iterations);
  }
  report.converged = false;
  return report;
}

// Cycles of one full sweep and up to full_sweep_every - 1 sweeps over the active contacts. The
// full sweep runs plain (conjugate directions restart after it) and alone decides convergence.
SolveReport GaussSeidel::solve_in_cycles(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                                         SweepExchange* exchange, JoiningContacts* joining)
{
  CycleWorkspace& work = cycle_;
  work.change_sq.resize(contacts.size());
  SolveReport report;
  ConjugateBeta conjugate;
  StallRescue rescue(settings_, stall_, exchange, contacts);
  bool sliding_images = has_sliding_images(contacts);
  double previous_full_residual = std::numeric_limits<double>::infinity();
  for (int full_sweeps = 1; report.iterations < settings_.max_iterations; full_sweeps++) {
    // The full sweep records no conjugate direction: the first active sweep, unpushed, does.
    SolverSettings full_sweep = rescue.sweeping();
    full_sweep.acceleration = Acceleration::none;
    SweepChange change = sweep_measuring(contacts.data(), contacts.data() + contacts.size(), velocity.data(),
                                         full_sweep, sliding_images, 0.0, work.change_sq.data());
    if (exchange) exchange->after_sweep(change);
    const bool converged = count_sweep(report, change, contacts.size(), settings_);
    rescue.add_sweep(change, report);
    if (observer_) observer_->after_full_sweep(report);
    // Contacts that join are active in the cycle: they have not been swept yet.
    if (joining && looks_for_joining(full_sweeps, converged) && joining->join(converged)) {
      work.change_sq.resize(contacts.size(), std::numeric_limits<double>::infinity());
      sliding_images = has_sliding_images(contacts);
    } else if (converged) {
      return report;
    }
    rescue.solve_kept_block(contacts, velocity, report);
    // After a restart from zero or a block solve, contacts the full sweep left quiet may change:
    // all are active.
    if (rescue.act(contacts, velocity, report) && (report.cold_restarts > 0 || report.block_solves > 0))
      std::fill(work.change_sq.begin(), work.change_sq.end(), std::numeric_limits<double>::infinity());
    select_active(work, contacts, change.quiet_change_sq(settings_.norm, settings_.tolerance, quiet_fraction));
    conjugate.restart(report.residual < previous_full_residual);
    previous_full_residual = report.residual;
    double beta = 0.0;
    for (int k = 1; k < settings_.full_sweep_every && report.iterations < settings_.max_iterations; k++) {
      SweepChange active_change =
          sweep_active(work, contacts, velocity.data(), rescue.sweeping(), sliding_images, beta);
      if (exchange) exchange->after_sweep(active_change);
      const bool active_converged = count_sweep(report, active_change, work.active.size(), settings_);
      rescue.add_sweep(active_change, report);
      if (active_converged) break;
      if (rescue.sweeping().acceleration == Acceleration::conjugate)
        beta = conjugate.next(active_change.sum_change_sq, report.iterations, settings_.max_iterations);
    }
  }
  report.converged = false;
  return report;
}

// Written so that NaN fails every test. A tolerance of 1 or more is met by any first sweep (the
// norm compares the sweep's change with the impulses' scale), one of 0 runs the cap's sweeps; relaxation above 1 is not offered
// (over-relaxation gained nothing in time: doc/benchmarks.md).
std::string check(const SolverSettings& settings)
{
  if (!(settings.tolerance >= 0.0 && settings.tolerance < 1.0))
    return refusal("tolerance", "in [0,1)", settings.tolerance);
  if (settings.max_iterations < 1) return refusal("max_iterations", ">= 1", settings.max_iterations);
  if (!(settings.relaxation > 0.0 && settings.relaxation <= 1.0))
    return refusal("relaxation", "in (0,1]", settings.relaxation);
  if (settings.full_sweep_every < 1) return refusal("full_sweep_every", ">= 1", settings.full_sweep_every);
  if (settings.stall_window < 0) return refusal("stall_window", ">= 0", settings.stall_window);
  if (!(settings.stall_coherence > 0.0 && settings.stall_coherence < 1.0))
    return refusal("stall_coherence", "in (0,1)", settings.stall_coherence);
  if (!(settings.stall_relaxation > 0.0 && settings.stall_relaxation <= 1.0))
    return refusal("stall_relaxation", "in (0,1]", settings.stall_relaxation);
  if (settings.stall_block < 0) return refusal("stall_block", ">= 0", settings.stall_block);
  if (settings.stall_block_every < 0) return refusal("stall_block_every", ">= 0", settings.stall_block_every);
  return {};
}

GaussSeidel::GaussSeidel(const SolverSettings& settings) : settings_(settings)
{
  const std::string problem = check(settings_);
  if (!problem.empty()) throw std::invalid_argument(problem);
}

SolveReport GaussSeidel::solve(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                               SweepExchange* exchange, JoiningContacts* joining)
{
  // Without an exchange and without contacts there is nothing to do unless some join (a
  // problem without contacts has converged); with an exchange, every rank takes part in every
  // sweep's exchange, contacts or not.
  if (contacts.empty() && !exchange && !(joining && joining->join(true))) return {};
  return settings_.full_sweep_every > 1 ? solve_in_cycles(contacts, velocity, exchange, joining)
                                        : solve_in_full_sweeps(contacts, velocity, exchange, joining);
}

SolveReport solve_gauss_seidel(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                               const SolverSettings& settings, SweepExchange* exchange, JoiningContacts* joining)
{
  return GaussSeidel(settings).solve(contacts, velocity, exchange, joining);
}

}  // namespace cd
