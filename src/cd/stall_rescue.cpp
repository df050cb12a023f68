// The stall rescue (cd/stall_rescue.h).
#include "cd/stall_rescue.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "cd/block_solve.h"

namespace cd {

namespace {

// The impulses taken off the velocities and set to zero: a solve starting again from nothing.
void remove_impulses(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity)
{
  for (Contact& c : contacts) {
    apply_impulse(c, {-c.impulse.n, -c.impulse.t}, velocity[c.body_a], velocity[c.body_b]);
    c.impulse = {};
    c.direction = {};
  }
}

}  // namespace

void StallWatch::start(const std::vector<Contact>& contacts, int iterations)
{
  if (window_ == 0) return;
  window_start_.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); k++) window_start_[k] = contacts[k].impulse;
  start_ = iterations;
  path_ = 0.0;
}

bool StallWatch::stalled(const std::vector<Contact>& contacts, int iterations)
{
  if (window_ == 0 || iterations - start_ < window_) return false;
  double sums[2] = {net_change_sq(contacts), path_};
  if (exchange_) exchange_->sum_over_ranks(sums, 2);
  if (std::sqrt(sums[0]) < coherence_ * sums[1]) return true;
  start(contacts, iterations);
  return false;
}

double StallWatch::net_change_sq(const std::vector<Contact>& contacts) const
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

StallRescue::StallRescue(const GaussSeidelSettings& settings, StallWorkspace& work, SweepExchange* exchange,
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

void StallRescue::solve_kept_block(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                                   SolveReport& report)
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

bool StallRescue::act(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report)
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

bool StallRescue::act_by_blocks(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                                SolveReport& report)
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

bool StallRescue::cycles_slowly(const std::vector<Contact>& contacts, const SolveReport& report)
{
  if (!(report.residual >= lowest_residual_)) lowest_residual_ = report.residual, lowest_at_ = report.iterations;
  if (!slow_watch_.ends(report.iterations)) return false;
  const bool progressed = lowest_at_ > slow_watch_.started();
  const bool went_back_and_forth = slow_watch_.stalled(contacts, report.iterations);
  if (went_back_and_forth && progressed) slow_watch_.start(contacts, report.iterations);
  return went_back_and_forth && !progressed;
}

void StallRescue::keep(const std::vector<int>& block, int budget)
{
  std::vector<int> joined;
  std::set_union(kept_.begin(), kept_.end(), block.begin(), block.end(), std::back_inserter(joined));
  kept_ = static_cast<int>(joined.size()) <= budget ? std::move(joined) : block;
}

void StallRescue::relax_unaccelerated(double relaxation)
{
  sweeping_.relaxation = relaxation;
  sweeping_.acceleration = Acceleration::none;
}

}  // namespace cd
