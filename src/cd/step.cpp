// The step of the core (cd/step.h): its settings checked, the solve loop that lets watched pairs
// join, and the stages that MoreauJeanStep runs in order.
#include "cd/step.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "cd/refusal.h"
#include "cd/solver_registry.h"

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
SolveReport solve_step(ContactSolver& solver, StepContacts& contacts, BodySet& bodies, const StepParameters& step,
                       const StepSettings& settings, PairReach& reach, StepHost& host, SweepExchange* exchange)
{
  contacts.watch_only();
  ClosingPairs closing(contacts, bodies, step, exchange);
  JoiningContacts* during = settings.joining == Joining::during_solve ? &closing : nullptr;
  SolveReport report = solver.solve(contacts.solved, bodies.velocity, exchange, during);
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
    report.add(solver.solve(contacts.solved, bodies.velocity, exchange, during));
  }
  reach.end_step(needed);
  return report;
}

}  // namespace

namespace {

void require_sound(const StepSettings& settings)
{
  const std::string problem = check(settings);
  if (!problem.empty()) throw std::invalid_argument(problem);
}

}  // namespace

// Written so that NaN fails every test.
std::string check(const StepSettings& settings)
{
  if (!(settings.theta >= 0.5 && settings.theta <= 1.0)) return refusal("theta", "in [0.5,1]", settings.theta);
  // A step always asks for convergence: tolerance 0 (a fixed sweep count) is the solver's alone.
  if (!(settings.solver.tolerance > 0.0 && settings.solver.tolerance < 1.0))
    return refusal("tolerance", "in (0,1)", settings.solver.tolerance);
  const std::string solver_problem = check(settings.solver);  // the method's name and knobs
  if (!solver_problem.empty()) return solver_problem;
  if (settings.alert && !(*settings.alert >= 0.0)) return refusal("alert", ">= 0", *settings.alert);
  if (settings.max_solves < 1) return refusal("max_solves", ">= 1", settings.max_solves);
  return {};
}

MoreauJeanStep::MoreauJeanStep(const StepSettings& settings, std::uint64_t shuffle_seed)
    : settings_(settings), alert_(settings.alert.value_or(0.0)), reach_(alert_), shuffle_rng_(shuffle_seed)
{
  require_sound(settings_);
  solver_ = make_solver(settings_.solver);
}

void MoreauJeanStep::set_mean_diameter(double mean_diameter)
{
  if (!(mean_diameter > 0.0)) throw std::invalid_argument(refusal("the grains' mean diameter", "> 0", mean_diameter));
  alert_ = settings_.alert.value_or(default_alert_diameters * mean_diameter);
}

void MoreauJeanStep::prepare(const BodySet& bodies, double dt, StepHost& host)
{
  const StepParameters step{dt, settings_.theta};
  reach_.set_margin_floor(alert_);
  reach_.begin_step(bodies, step);
  contacts_.begin(bodies, step, alert_, settings_.warm_start);
  host.collect_pairs(reach_, -std::numeric_limits<double>::infinity(), reach_.margin(), contacts_);
  reorder(static_cast<int>(bodies.velocity.size()));
}

StepReport MoreauJeanStep::solve(BodySet& bodies, double dt, StepHost& host, SweepExchange* exchange)
{
  const StepParameters step{dt, settings_.theta};
  prepare(bodies, dt, host);
  if (keeping_problems_) {
    kept_.contacts = contacts_.solved;
    kept_.free_velocity = bodies.velocity;
  }
  apply_impulses(contacts_.solved, bodies.velocity);
  if (exchange) exchange->share_velocities();

  StepReport report;
  report.solve = solve_step(*solver_, contacts_, bodies, step, settings_, reach_, host, exchange);
  contacts_.for_each_loaded([&](const PairKey&, const Contact&, double) { ++report.loaded_contacts; });
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

}  // namespace cd
