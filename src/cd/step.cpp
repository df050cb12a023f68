#include "cd/step.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cd {

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

// The solve loop: solves the step's contacts, then lets watched pairs that the solution would
// drive into overlap join and solves again from where it stopped, looking wider first (through
// the host) if bodies gained more speed than the margin covers; at most settings.max_solves
// solves. The impulses must already be applied to bodies.velocity. The report sums the sweeps
// of every solve.
SolveReport solve_step(StepContacts& contacts, BodySet& bodies, const StepParameters& step,
                       const StepSettings& settings, PairReach& reach, StepHost& host, SweepExchange* exchange)
{
  contacts.watch_only();
  ClosingPairs closing(contacts, bodies, step, exchange);
  JoiningContacts* during = settings.joining == Joining::during_solve ? &closing : nullptr;
  SolveReport report = solve_gauss_seidel(contacts.solved, bodies.velocity, settings.solver, exchange, during);
  double needed = 0.0;
  for (int round = 1;; round++) {
    needed = std::max(needed, reach.needed_margin(bodies.velocity, step));
    const bool widened = needed > reach.margin();
    if (widened) {
      const double wider = reach.wider_margin(needed);
      host.collect_pairs(reach, reach.margin(), wider, contacts);
      reach.widen_to(wider);
    }
    if (round == settings.max_solves) break;
    // A solve that converged joining during its sweeps has just checked every watched pair at
    // these velocities: only pairs the wider look added are new (the vote is every rank's).
    const bool checked = during && report.converged && !widened;
    bool promoted = !checked && promote_closing_pairs(contacts, bodies, step);
    if (exchange) promoted = exchange->on_any_rank(promoted);
    if (!promoted) break;
    const SolveReport more = solve_gauss_seidel(contacts.solved, bodies.velocity, settings.solver, exchange, during);
    report.iterations += more.iterations;
    report.solves += 1;
    report.contact_updates += more.contact_updates;
    report.residual = more.residual;
    report.converged = more.converged;
  }
  reach.end_step(needed);
  return report;
}

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

  StepReport report;
  report.solve = solve_step(contacts_, bodies, step, settings_, reach_, host, exchange);
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
  shuffled_order(contacts_.solved.size(), shuffle_rng_, permutation_);
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
