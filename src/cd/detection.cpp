#include "cd/detection.h"

#include <algorithm>
#include <cmath>

namespace cd {

void PairReach::begin_step(const BodySet& bodies, const StepParameters& step)
{
  const double advance = step.advance();
  reach_.resize(bodies.velocity.size());
  for (std::size_t b = 0; b < reach_.size(); b++) {
    const BodyVelocity& v = bodies.velocity[b];
    reach_[b] = advance * std::sqrt(v.vx * v.vx + v.vy * v.vy);
  }
}

double PairReach::needed_margin(const std::vector<BodyVelocity>& velocity, const StepParameters& step) const
{
  const double advance = step.advance();
  double largest_gain = 0.0;  // m, advance times speed
  for (std::size_t b = 0; b < reach_.size(); b++) {
    const BodyVelocity& v = velocity[b];
    largest_gain = std::max(largest_gain, advance * std::sqrt(v.vx * v.vx + v.vy * v.vy) - reach_[b]);
  }
  return 2.0 * largest_gain;
}

void PairReach::end_step(double needed)
{
  margin_ = std::max(margin_floor_, wider_margin(needed));
}

void StepContacts::begin(const BodySet& bodies, const StepParameters& step, double alert, bool warm_start)
{
  solved.clear();
  keys.clear();
  gaps.clear();
  watched.clear();
  bodies_ = &bodies;
  step_ = step;
  alert_ = alert;
  warm_start_ = warm_start;
  watch_only_ = false;
}

void StepContacts::offer(const ContactGeometry& geometry, const ContactLaw& law, const PairKey& key, Local2 carried)
{
  const Contact frame = contact_frame(geometry);
  if (watch_only_ || !is_candidate(frame, geometry.gap, *bodies_, step_, alert_)) {
    watched.push_back({geometry, law, key});
    return;
  }
  solved.push_back(frame);
  keys.push_back(key);
  gaps.push_back(geometry.gap);
  prepare_mechanics(solved.back(), geometry.gap, law, *bodies_, step_);
  if (warm_start_) warm_start(solved.back(), carried);
}

void StepContacts::reorder(const std::vector<int>& permutation)
{
  reordered_.clear();
  reordered_keys_.clear();
  reordered_gaps_.clear();
  for (const int k : permutation) {
    reordered_.push_back(solved[k]);
    reordered_keys_.push_back(keys[k]);
    reordered_gaps_.push_back(gaps[k]);
  }
  solved.swap(reordered_);
  keys.swap(reordered_keys_);
  gaps.swap(reordered_gaps_);
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
    contacts.solved.push_back(prepared_contact(pair.geometry, pair.law, bodies, step));
    contacts.keys.push_back(pair.key);
    contacts.gaps.push_back(pair.geometry.gap);
  }
  contacts.watched.resize(kept);
  return contacts.solved.size() > before;
}

bool in_branch_sums(const StepContacts& contacts, std::size_t k)
{
  const Contact& c = contacts.solved[k];
  const bool finite = std::isfinite(c.impulse.n) && std::isfinite(c.impulse.t);
  return !(finite && c.impulse.n <= 0.0);  // as for_each_loaded
}

BranchImpulseSums branch_impulse(const StepContacts& contacts, std::size_t k)
{
  const Contact& c = contacts.solved[k];
  const double branch = c.lever_a + c.lever_b + contacts.gaps[k];
  const double lx = branch * c.normal_x, ly = branch * c.normal_y;
  const WorldImpulse p = world_impulse(c, c.impulse);
  return {lx * p.x, ly * p.y, lx * p.y, ly * p.x};
}

BranchImpulseSums branch_impulse_sums(const StepContacts& contacts)
{
  BranchImpulseSums sums;
  for (std::size_t k = 0; k < contacts.solved.size(); k++) {
    if (!in_branch_sums(contacts, k)) continue;
    const BranchImpulseSums one = branch_impulse(contacts, k);
    sums.xx += one.xx;
    sums.yy += one.yy;
    sums.xy += one.xy;
    sums.yx += one.yx;
  }
  return sums;
}

}  // namespace cd
