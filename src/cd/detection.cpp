#include "cd/detection.h"

#include <algorithm>
#include <cmath>

namespace cd {

namespace {

// Next step's margin is this many times what this step needed: a flow changes little from one
// step to the next, and a margin a little too wide costs a few more pairs looked at.
constexpr double margin_growth = 1.5;

}  // namespace

void PairReach::begin_step(const BodySet& bodies, const StepParameters& step)
{
  const double advance = step.theta * step.dt;
  reach_.resize(bodies.velocity.size());
  for (std::size_t b = 0; b < reach_.size(); b++) {
    const BodyVelocity& v = bodies.velocity[b];
    reach_[b] = advance * std::sqrt(v.vx * v.vx + v.vy * v.vy);
  }
}

double PairReach::needed_margin(const std::vector<BodyVelocity>& velocity, const StepParameters& step) const
{
  const double advance = step.theta * step.dt;
  double largest_gain = 0.0;  // m, advance times speed
  for (std::size_t b = 0; b < reach_.size(); b++) {
    const BodyVelocity& v = velocity[b];
    largest_gain = std::max(largest_gain, advance * std::sqrt(v.vx * v.vx + v.vy * v.vy) - reach_[b]);
  }
  return 2.0 * largest_gain;
}

void PairReach::end_step(double needed)
{
  margin_ = std::max(margin_floor_, margin_growth * needed);
}

void StepContacts::begin(const BodySet& bodies, const StepParameters& step, double alert)
{
  solved.clear();
  keys.clear();
  watched.clear();
  bodies_ = &bodies;
  step_ = step;
  alert_ = alert;
  watch_only_ = false;
}

void StepContacts::offer(const ContactGeometry& geometry, const ContactLaw& law, const PairKey& key)
{
  const Contact frame = contact_frame(geometry);
  if (watch_only_ || !is_candidate(frame, *bodies_, step_, alert_)) {
    watched.push_back({geometry, law, key});
    return;
  }
  solved.push_back(frame);
  keys.push_back(key);
  prepare_mechanics(solved.back(), law, *bodies_, step_);
}

void StepContacts::reorder(const std::vector<int>& permutation)
{
  reordered_.clear();
  reordered_keys_.clear();
  for (const int k : permutation) {
    reordered_.push_back(solved[k]);
    reordered_keys_.push_back(keys[k]);
  }
  solved.swap(reordered_);
  keys.swap(reordered_keys_);
}

bool promote_closing_pairs(StepContacts& contacts, const BodySet& bodies, const StepParameters& step)
{
  const std::size_t before = contacts.solved.size();
  std::size_t kept = 0;
  for (WatchedPair& pair : contacts.watched) {
    if (!closes_after_solve(pair.geometry, bodies.velocity, step)) {
      contacts.watched[kept++] = pair;
      continue;
    }
    contacts.solved.push_back(contact_frame(pair.geometry));
    prepare_mechanics(contacts.solved.back(), pair.law, bodies, step);
    contacts.keys.push_back(pair.key);
  }
  contacts.watched.resize(kept);
  return contacts.solved.size() > before;
}

namespace {

// Watched pairs joining a running solve (Joining::during_solve).
class ClosingPairs : public JoiningContacts {
 public:
  ClosingPairs(StepContacts& contacts, const BodySet& bodies, const StepParameters& step, SweepExchange* exchange)
      : contacts_(contacts), bodies_(bodies), step_(step), exchange_(exchange)
  {
  }
  bool join(bool converged) override
  {
    const bool joined = promote_closing_pairs(contacts_, bodies_, step_);
    return converged && exchange_ ? exchange_->on_any_rank(joined) : joined;
  }

 private:
  StepContacts& contacts_;
  const BodySet& bodies_;
  StepParameters step_;
  SweepExchange* exchange_;
};

}  // namespace

SolveReport solve_step(StepContacts& contacts, BodySet& bodies, const StepParameters& step,
                       const SolverSettings& settings, PairReach& reach, PairCollector& collector,
                       SweepExchange* exchange, int max_rounds, Joining joining)
{
  contacts.watch_only();
  ClosingPairs closing(contacts, bodies, step, exchange);
  JoiningContacts* during = joining == Joining::during_solve ? &closing : nullptr;
  SolveReport report = solve_gauss_seidel(contacts.solved, bodies.velocity, settings, exchange, during);
  double needed = 0.0;
  for (int round = 1;; round++) {
    needed = std::max(needed, reach.needed_margin(bodies.velocity, step));
    const bool widened = needed > reach.margin();
    if (widened) {
      const double wider = margin_growth * needed;
      collector.collect_between(reach.margin(), wider);
      reach.widen_to(wider);
    }
    if (round == max_rounds) break;
    // A solve that converged joining during its sweeps has just checked every watched pair at
    // these velocities: only pairs the wider look added are new (the vote is every rank's).
    const bool checked = during && report.converged && !widened;
    bool promoted = !checked && promote_closing_pairs(contacts, bodies, step);
    if (exchange) promoted = exchange->on_any_rank(promoted);
    if (!promoted) break;
    const SolveReport more = solve_gauss_seidel(contacts.solved, bodies.velocity, settings, exchange, during);
    report.iterations += more.iterations;
    report.solves += 1;
    report.contact_updates += more.contact_updates;
    report.residual = more.residual;
    report.converged = more.converged;
  }
  reach.end_step(needed);
  return report;
}

OverlapSums measure_overlaps(const StepContacts& contacts, const std::vector<BodyVelocity>& velocity,
                             const StepParameters& step)
{
  auto overlap_of = [&](const Contact& c) {
    const double u_n = relative_velocity(c, velocity[c.body_a], velocity[c.body_b]).n;
    return std::max(0.0, -end_of_step_gap(c.gap, u_n, step));
  };
  OverlapSums sums;
  for (const Contact& c : contacts.solved) {
    const double overlap = overlap_of(c);
    sums.deepest = std::max(sums.deepest, overlap);
    sums.total += overlap;
  }
  for (const WatchedPair& pair : contacts.watched) {
    const double overlap = -end_of_step_gap(pair.geometry.gap, normal_velocity(pair.geometry, velocity), step);
    sums.deepest = std::max(sums.deepest, overlap);
  }
  return sums;
}

}  // namespace cd
