// Which pairs a step solves and which it only watches, and how far it looks for them.
//
// A pair (a, b) with gap g can close within the step only if theta dt (|v_a| + |v_b|) > g for
// the velocities it ends the step with. Before the solve only the free velocities are known, so
// a pair is looked at (its geometry computed) only if
//     g <= theta dt (|v_a^free| + |v_b^free|) + margin,
// a test on squared centre distances, without a square root. After each solve the margin is
// checked against the speed the bodies actually gained: a body faster than its free speed by
// more than margin / (2 theta dt) could close a pair that was never looked at, and the caller
// is asked to look again, wider. The margin of the next step follows what this one needed, so
// that the wider look stays rare.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cd/contact.h"

namespace cd {

class PairReach {
 public:
  // margin_floor: the smallest margin (m), at least the candidates' alert distance.
  explicit PairReach(double margin_floor = 0.0) : margin_floor_(margin_floor), margin_(margin_floor) {}

  // Reach theta dt |v^free| of every body, from the free velocities of the step.
  void begin_step(const BodySet& bodies, const StepParameters& step);

  // True if disks a and b (b at its periodic image nearest to a) may meet within the step
  // with a gap of at most their reach plus `margin` (m).
  bool within(int body_a, const Disk& a, int body_b, const Disk& b, double margin) const
  {
    const double dx = a.x - b.x;
    const double dy = a.y - b.y;
    const double limit = a.radius + b.radius + reach_[body_a] + reach_[body_b] + margin;
    return dx * dx + dy * dy <= limit * limit;
  }

  // The looks of a step: a pair (or a disk and a wall at `gap`) is looked at by the look out to
  // to_margin unless an earlier look, out to from_margin, took it (-infinity: no earlier look).
  bool in_look(int body_a, const Disk& a, int body_b, const Disk& b, double from_margin, double to_margin) const
  {
    if (!within(body_a, a, body_b, b, to_margin)) return false;
    return !std::isfinite(from_margin) || !within(body_a, a, body_b, b, from_margin);
  }
  bool wall_in_look(int body, double gap, double from_margin) const { return gap > reach_[body] + from_margin; }

  double margin() const { return margin_; }
  // A new floor (the alert distance once the grain size is known); the margin rises to it.
  void set_margin_floor(double floor)
  {
    margin_floor_ = floor;
    margin_ = std::max(margin_, floor);
  }
  double reach(int body) const { return reach_[body]; }  // m

  // The margin the solved velocities need: 2 theta dt times the largest speed gain of a body
  // over its free speed (0 if none got faster).
  double needed_margin(const std::vector<BodyVelocity>& velocity, const StepParameters& step) const;

  // The margin of a wider look for a solve that needs `needed`, with room to spare.
  double wider_margin(double needed) const { return margin_growth * needed; }
  // The caller has looked at pairs out to `margin`.
  void widen_to(double margin) { margin_ = margin; }

  // Next step's margin: what this step needed, with room to spare, never below the floor.
  void end_step(double needed);

 private:
  // A margin is this many times what a step needed: a flow changes little from one step to the
  // next, and a margin a little too wide costs a few more pairs looked at.
  static constexpr double margin_growth = 1.5;

  double margin_floor_;
  double margin_;
  std::vector<double> reach_;  // per body (m)
};

// Identifies a pair from one step to the next: the host's storage row of the pair's keeper
// (e.g. the atom with the smaller ID) and the partner's id within that row (e.g. the other
// atom's ID, or a wall's slot). An id, not a number: a host that stores it among doubles
// (LAMMPS's per-atom arrays, cd::impulse_row) converts it there.
struct PairKey {
  int row = -1;
  std::int64_t partner = 0;
};

// A looked-at pair left out of the solve: its geometry, its law and its key. Kept apart from
// cd::Contact (a third of its size): a solve checks every watched pair several times.
struct WatchedPair {
  ContactGeometry geometry;
  ContactLaw law;
  PairKey key;
};

// The contacts of one step: those solved, in sweep order, each with its key and its gap at the
// predicted configuration (keys[k] and gaps[k] are solved[k]'s: whatever reorders the contacts
// reorders them), and those only watched.
class StepContacts {
 public:
  std::vector<Contact> solved;
  std::vector<PairKey> keys;
  std::vector<double> gaps;  // m
  std::vector<WatchedPair> watched;

  // Starts a step: offered pairs are solved if candidates (is_candidate at `alert`, m), watched
  // otherwise; solved ones start from their carried impulse if `warm_start` (cd::warm_start).
  // `bodies` must hold the free velocities and outlive the collection.
  void begin(const BodySet& bodies, const StepParameters& step, double alert, bool warm_start);
  // From now on offered pairs are watched whatever their velocity: found during the solve, they
  // join only by promotion (promote_closing_pairs).
  void watch_only() { watch_only_ = true; }

  // A pair the host found near enough to look at, with the impulse it carried at the end of the
  // previous step ({0, 0} if none).
  void offer(const ContactGeometry& geometry, const ContactLaw& law, const PairKey& key, Local2 carried);

  // Calls visit(key, contact, gap) for every solved contact whose impulse the next step starts
  // from: loaded (p_n > 0), or not finite (the host reports it: it knows the bodies' names).
  template <class Visit>
  void for_each_loaded(Visit&& visit) const
  {
    for (std::size_t k = 0; k < solved.size(); k++) {
      const Local2 p = solved[k].impulse;
      if (std::isfinite(p.n) && std::isfinite(p.t) && p.n <= 0.0) continue;
      visit(keys[k], solved[k], gaps[k]);
    }
  }

  // Puts the solved contacts (and their keys and gaps) in the order of `permutation`, whose k-th entry
  // is the old index of the new k-th contact.
  void reorder(const std::vector<int>& permutation);

  std::size_t memory_bytes() const
  {
    return (solved.capacity() + reordered_.capacity()) * sizeof(Contact) +
           (keys.capacity() + reordered_keys_.capacity()) * sizeof(PairKey) +
           (gaps.capacity() + reordered_gaps_.capacity()) * sizeof(double) + watched.capacity() * sizeof(WatchedPair);
  }

 private:
  const BodySet* bodies_ = nullptr;
  StepParameters step_;
  double alert_ = 0.0;
  bool warm_start_ = true;
  bool watch_only_ = false;
  std::vector<Contact> reordered_;  // scratch of reorder
  std::vector<PairKey> reordered_keys_;
  std::vector<double> reordered_gaps_;
};

// Moves the watched pairs that would overlap at the end of the step with the solved velocities
// (closes_after_solve) to the solved contacts, prepared, keys and gaps with them. True if any moved.
bool promote_closing_pairs(StepContacts& contacts, const BodySet& bodies, const StepParameters& step);

// The contact part of the pressure tensor times area and step (N s m), compressive positive: over
// the loaded contacts (StepContacts::for_each_loaded) between two bodies (not walls), the branch
// vector l (from b's centre to a's, at the predicted configuration; from the contact point on a wall)
// times a's impulse p, xy = l_x p_y.
struct BranchImpulseSums {
  double xx = 0.0;
  double yy = 0.0;
  double xy = 0.0;
  double yx = 0.0;
};

// l p of solved contact k, and whether it enters the sums (a loaded contact, walls' too).
bool in_branch_sums(const StepContacts& contacts, std::size_t k);
BranchImpulseSums branch_impulse(const StepContacts& contacts, std::size_t k);

BranchImpulseSums branch_impulse_sums(const StepContacts& contacts);

// The sums body by body, as a pair style splits its virial: visit(body, share) for each contact
// in the sums, half to each body when both move, all of it to the one that moves against an
// immovable body (a wall or an obstacle, inverse mass 0). The shares add up to branch_impulse_sums.
template <class Visit>
void for_each_branch_impulse_share(const StepContacts& contacts, Visit&& visit)
{
  for (std::size_t k = 0; k < contacts.solved.size(); k++) {
    if (!in_branch_sums(contacts, k)) continue;
    const Contact& c = contacts.solved[k];
    const BranchImpulseSums whole = branch_impulse(contacts, k);
    const bool a_moves = c.inv_mass_a > 0.0, b_moves = c.inv_mass_b > 0.0;
    if (a_moves && b_moves) {
      const BranchImpulseSums half{0.5 * whole.xx, 0.5 * whole.yy, 0.5 * whole.xy, 0.5 * whole.yx};
      visit(c.body_a, half);
      visit(c.body_b, half);
    } else {
      visit(a_moves || !b_moves ? c.body_a : c.body_b, whole);
    }
  }
}

}  // namespace cd
