#include "cd/step.h"

#include <cmath>
#include <limits>
#include <utility>

namespace cd {

namespace {

// The wider look cd::solve_step may ask for, through the host.
class HostPairs : public PairCollector {
 public:
  HostPairs(StepHost& host, const PairReach& reach, StepContacts& contacts)
      : host_(host), reach_(reach), contacts_(contacts)
  {
  }
  void collect_between(double from_margin, double to_margin) override
  {
    host_.collect_pairs(reach_, from_margin, to_margin, contacts_);
  }

 private:
  StepHost& host_;
  const PairReach& reach_;
  StepContacts& contacts_;
};

}  // namespace

MoreauJeanStep::MoreauJeanStep(const StepSettings& settings, std::uint64_t shuffle_seed)
    : settings_(settings), reach_(settings.alert), shuffle_rng_(shuffle_seed)
{
}

void MoreauJeanStep::prepare(const BodySet& bodies, double dt, StepHost& host)
{
  const StepParameters step{dt, settings_.theta};
  reach_.set_margin_floor(settings_.alert);
  reach_.begin_step(bodies, step);
  contacts_.begin(bodies, step, settings_.alert);
  host.collect_pairs(reach_, -std::numeric_limits<double>::infinity(), reach_.margin(), contacts_);
  reorder(static_cast<int>(bodies.velocity.size()));
  if (settings_.warm_start) warm_start(host);
}

StepReport MoreauJeanStep::solve(BodySet& bodies, double dt, StepHost& host, SweepExchange* exchange)
{
  const StepParameters step{dt, settings_.theta};
  prepare(bodies, dt, host);
  apply_impulses(contacts_.solved, bodies.velocity);
  if (exchange) exchange->share_velocities();

  HostPairs wider(host, reach_, contacts_);
  StepReport report;
  report.solve = solve_step(contacts_, bodies, step, settings_.solver, reach_, wider, exchange, settings_.max_solves,
                            settings_.joining);
  report.overlaps = measure_overlaps(contacts_, bodies.velocity, step);
  report.loaded_contacts = store_impulses(host);
  return report;
}

void MoreauJeanStep::reorder(int body_count)
{
  if (settings_.order == ContactOrder::as_offered) return;
  if (settings_.order == ContactOrder::interleaved) {
    contacts_.reorder(interleaved_order(contacts_.solved, body_count));
    return;
  }
  permutation_.resize(contacts_.solved.size());
  for (std::size_t k = 0; k < permutation_.size(); k++) permutation_[k] = static_cast<int>(k);
  for (std::size_t k = permutation_.size(); k > 1; k--) {
    std::uniform_int_distribution<std::size_t> pick(0, k - 1);
    std::swap(permutation_[k - 1], permutation_[pick(shuffle_rng_)]);
  }
  contacts_.reorder(permutation_);
}

void MoreauJeanStep::warm_start(const StepHost& host)
{
  for (std::size_t k = 0; k < contacts_.solved.size(); k++)
    cd::warm_start(contacts_.solved[k], host.carried_impulse(contacts_.keys[k]));
}

// Keeps only loaded contacts' impulses; a non-finite one is the host's to report (it knows the
// bodies' names): stored as it is.
int MoreauJeanStep::store_impulses(StepHost& host) const
{
  host.forget_impulses();
  int loaded = 0;
  for (std::size_t k = 0; k < contacts_.solved.size(); k++) {
    const Local2 p = contacts_.solved[k].impulse;
    if (std::isfinite(p.n) && std::isfinite(p.t) && p.n <= 0.0) continue;
    host.remember_impulse(contacts_.keys[k], p);
    ++loaded;
  }
  return loaded;
}

}  // namespace cd
