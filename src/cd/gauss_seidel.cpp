// The Gauss–Seidel sweeps over prepared contacts and the solves made of them (cd/gauss_seidel.h);
// their stall rescue is cd/stall_rescue.h's.
#include "cd/gauss_seidel.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include "cd/newton_polish.h"
#include "cd/refusal.h"
#include "cd/stall_rescue.h"

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

// The impulse p (every other impulse frozen) or, under relaxation w, w p + (1 - w) p_previous;
// over-relaxed (w > 1, only in the sweeps of over_relaxation), the mix may leave the cone and is
// put back on it.
template <bool over_relaxes>
inline Local2 relaxed(Local2 p, Local2 previous, double relaxation, double mu)
{
  if (relaxation == 1.0) return p;
  const Local2 mixed{relaxation * p.n + (1.0 - relaxation) * previous.n,
                     relaxation * p.t + (1.0 - relaxation) * previous.t};
  if constexpr (over_relaxes) return relaxation > 1.0 ? solve_coulomb_disk(mixed, mu) : mixed;
  return mixed;
}

// The face of the Coulomb law an impulse lies on: 0 open; closed, 1 sticking, 2 and 3 sliding
// forward and backward (4 at mu = 0). Without branches: the faces of a sweep's contacts follow
// no pattern a branch predictor could learn.
inline int law_face(Local2 p, double mu)
{
  const double bound = mu * p.n;
  return (p.n > 0.0) * (1 + (p.t >= bound) + 2 * (p.t <= -bound));
}

// Counts a local solve that moves the contact's impulse to another face of its law.
template <bool over_relaxes>
inline void record_face(SweepChange& change, Local2 previous, Local2 local, double mu)
{
  if constexpr (over_relaxes) change.face_changes += law_face(local, mu) != law_face(previous, mu);
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
template <ConvergenceNorm norm, bool conjugate, bool sliding_images, bool over_relaxes>
[[gnu::always_inline]] inline double update_frictional(Contact& c, BodyVelocity* velocity, double relaxation,
                                                       double beta, SweepChange& change)
{
  BodyVelocity& a = velocity[c.body_a];
  BodyVelocity& b = velocity[c.body_b];
  const Local2 u = swept_law_velocity<sliding_images>(c, a, b);
  const Local2 stick{c.impulse.n - c.delassus.inverse_nn * u.n, c.impulse.t - c.delassus.inverse_tt * u.t};
  const Local2 local = solve_coulomb_disk(stick, c.mu);
  const Local2 solved = relaxed<over_relaxes>(local, c.impulse, relaxation, c.mu);
  record_face<over_relaxes>(change, c.impulse, local, c.mu);
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
template <ConvergenceNorm norm, bool conjugate, bool over_relaxes>
[[gnu::always_inline]] inline double update_frictionless(Contact& c, BodyVelocity* velocity, double relaxation,
                                                         double beta, SweepChange& change)
{
  BodyVelocity& a = velocity[c.body_a];
  BodyVelocity& b = velocity[c.body_b];
  const double stick_n = c.impulse.n - c.delassus.inverse_nn * law_velocity(c, a, b).n;
  const double local_n = std::max(stick_n, 0.0);
  const double solved_n = relaxed<over_relaxes>({local_n, 0.0}, c.impulse, relaxation, 0.0).n;
  record_face<over_relaxes>(change, c.impulse, {local_n, 0.0}, 0.0);
  const double velocity_change = c.delassus.nn * (local_n - c.impulse.n);
  record_change<norm>(change, {velocity_change, 0.0}, {c.delassus.nn * solved_n, 0.0});
  const double p_n = accelerated<conjugate>(c, {solved_n, 0.0}, beta).n;
  const double dp_n = p_n - c.impulse.n;
  c.impulse.n = p_n;
  apply_normal_impulse(c, dp_n, a, b);
  return velocity_change * velocity_change;
}

// The local solve of one contact, its kind chosen per contact: a branch per contact rather
// than one sweep per kind serves scenes that mix mu = 0 with friction (mu/types, rough walls).
// Returns |W dp|^2 of the local solve.
template <class Kind>
[[gnu::always_inline]] inline double update_contact(Contact& c, BodyVelocity* velocity, bool shortcut,
                                                    double relaxation, double beta, SweepChange& change)
{
  if (shortcut && c.mu == 0.0)
    return update_frictionless<Kind::norm, Kind::conjugate, Kind::over_relaxes>(c, velocity, relaxation, beta, change);
  return update_frictional<Kind::norm, Kind::conjugate, Kind::sliding_images, Kind::over_relaxes>(
      c, velocity, relaxation, beta, change);
}

template <ConvergenceNorm norm_, bool conjugate_, bool sliding_images_, bool over_relaxes_>
struct SweepKind {
  static constexpr ConvergenceNorm norm = norm_;
  static constexpr bool conjugate = conjugate_;
  static constexpr bool sliding_images = sliding_images_;
  static constexpr bool over_relaxes = over_relaxes_;
};

template <bool sliding_images, bool over_relaxes, class Loop>
SweepChange for_kind(ConvergenceNorm norm, const GaussSeidelSettings& settings, Loop loop)
{
  const bool quadratic = norm == ConvergenceNorm::quadratic;
  if (settings.acceleration == Acceleration::conjugate)
    return quadratic ? loop(SweepKind<ConvergenceNorm::quadratic, true, sliding_images, over_relaxes>{})
                     : loop(SweepKind<ConvergenceNorm::maximum, true, sliding_images, over_relaxes>{});
  return quadratic ? loop(SweepKind<ConvergenceNorm::quadratic, false, sliding_images, over_relaxes>{})
                   : loop(SweepKind<ConvergenceNorm::maximum, false, sliding_images, over_relaxes>{});
}

// The kinds of over_relaxation (its faces counted, its impulses put back on their cones), kept
// out of line so that the compiler lays out the default kinds' loops as it would without them.
template <class Loop>
[[gnu::noinline]] SweepChange for_over_relaxing_kind(ConvergenceNorm norm, const GaussSeidelSettings& settings,
                                                     bool sliding_images, Loop loop)
{
  return sliding_images ? for_kind<true, true>(norm, settings, loop) : for_kind<false, true>(norm, settings, loop);
}

// Calls loop(SweepKind<norm, conjugate, sliding_images, over_relaxes>{}) for the norm, the
// settings' acceleration, the contacts' images and whether over_relaxation is on, so that the
// sweep loops are compiled once per kind. The loops copy the settings they read into locals: a
// store to a velocity could otherwise alias them and force a reload per contact.
template <class Loop>
SweepChange for_kind(ConvergenceNorm norm, const GaussSeidelSettings& settings, bool sliding_images, Loop loop)
{
  if (settings.over_relaxation != 1.0) return for_over_relaxing_kind(norm, settings, sliding_images, loop);
  return sliding_images ? for_kind<true, false>(norm, settings, loop) : for_kind<false, false>(norm, settings, loop);
}

// A sweep over [first, last); with `change_sq`, each contact's |W dp|^2 lands in it.
SweepChange sweep_measuring(Contact* first, Contact* last, BodyVelocity* velocity, ConvergenceNorm norm,
                            const GaussSeidelSettings& settings, bool sliding_images, double beta, double* change_sq)
{
  return for_kind(norm, settings, sliding_images, [&](auto kind) {
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

// A sweep over the listed contacts, in the list's order. Out of line: inlined in the solve's cycle,
// its loops shared registers with the cycle's bookkeeping (0.7 % more instructions on the chute).
[[gnu::noinline]] SweepChange sweep_listed(Contact* contacts, const std::vector<int>& listed, BodyVelocity* velocity,
                                           ConvergenceNorm norm, const GaussSeidelSettings& settings,
                                           bool sliding_images, double beta)
{
  return for_kind(norm, settings, sliding_images, [&](auto kind) {
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
  return sweep_measuring(first, last, velocity, settings.norm, settings.gauss_seidel, has_sliding_images(first, last),
                         beta, nullptr);
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

  // Starts the directions afresh for a new cycle of GaussSeidelSettings::full_sweep_every, in
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

// The next sweep's knobs: over-relaxed once the sweeps since the last full one changed no law face,
// unless the stall rescue relaxes them.
GaussSeidelSettings next_sweep(const GaussSeidelSettings& rescue_sweeping, bool faces_settled)
{
  GaussSeidelSettings settings = rescue_sweeping;
  if (faces_settled && settings.relaxation == 1.0) settings.relaxation = settings.over_relaxation;
  return settings;
}

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
                         BodyVelocity* velocity, ConvergenceNorm norm, const GaussSeidelSettings& settings,
                         bool sliding_images, double beta)
{
  SweepChange change = sweep_listed(contacts.data(), work.active, velocity, norm, settings, sliding_images, beta);
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
  StallRescue rescue(settings_.gauss_seidel, stall_, exchange, contacts);
  NewtonPolish polish(settings_, exchange);
  bool sliding_images = has_sliding_images(contacts);
  bool faces_settled = false;
  double beta = 0.0;
  while (report.iterations < settings_.max_iterations) {
    SweepChange change =
        sweep_measuring(contacts.data(), contacts.data() + contacts.size(), velocity.data(), settings_.norm,
                        next_sweep(rescue.sweeping(), faces_settled), sliding_images, beta, nullptr);
    if (exchange) exchange->after_sweep(change);
    faces_settled = change.face_changes == 0.0;
    const bool converged = count_sweep(report, change, contacts.size(), settings_);
    rescue.add_sweep(change, report);
    if (observer_) observer_->after_full_sweep(report);
    const bool joined = joining && looks_for_joining(report.iterations, converged) && joining->join(converged);
    if (joined) sliding_images = has_sliding_images(contacts);
    if (converged && !joined) return report;
    rescue.solve_kept_block(contacts, velocity, report);
    if (polish.act(contacts, velocity, report) || rescue.act(contacts, velocity, report)) beta = 0.0;
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
  StallRescue rescue(settings_.gauss_seidel, stall_, exchange, contacts);
  NewtonPolish polish(settings_, exchange);
  bool sliding_images = has_sliding_images(contacts);
  double previous_full_residual = std::numeric_limits<double>::infinity();
  bool faces_settled = false;
  for (int full_sweeps = 1; report.iterations < settings_.max_iterations; full_sweeps++) {
    // The full sweep records no conjugate direction: the first active sweep, unpushed, does.
    GaussSeidelSettings full_sweep = next_sweep(rescue.sweeping(), faces_settled);
    full_sweep.acceleration = Acceleration::none;
    SweepChange change = sweep_measuring(contacts.data(), contacts.data() + contacts.size(), velocity.data(),
                                         settings_.norm, full_sweep, sliding_images, 0.0, work.change_sq.data());
    if (exchange) exchange->after_sweep(change);
    faces_settled = change.face_changes == 0.0;
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
    // A polish kept: the next full sweep measures it.
    if (polish.act(contacts, velocity, report)) {
      conjugate.restart(true);
      previous_full_residual = report.residual;
      continue;
    }
    // After a restart from zero or a block solve, contacts the full sweep left quiet may change:
    // all are active.
    if (rescue.act(contacts, velocity, report) && (report.cold_restarts > 0 || report.block_solves > 0))
      std::fill(work.change_sq.begin(), work.change_sq.end(), std::numeric_limits<double>::infinity());
    select_active(work, contacts, change.quiet_change_sq(settings_.norm, settings_.tolerance, quiet_fraction));
    conjugate.restart(report.residual < previous_full_residual);
    previous_full_residual = report.residual;
    double beta = 0.0;
    for (int k = 1; k < settings_.gauss_seidel.full_sweep_every && report.iterations < settings_.max_iterations; k++) {
      SweepChange active_change = sweep_active(work, contacts, velocity.data(), settings_.norm,
                                               next_sweep(rescue.sweeping(), faces_settled), sliding_images, beta);
      if (exchange) exchange->after_sweep(active_change);
      faces_settled = faces_settled && active_change.face_changes == 0.0;
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

// Written so that NaN fails every test. relaxation stays at most 1: over-relaxing every sweep,
// faces changing or not, gained nothing in time (doc/benchmarks.md); over_relaxation waits for
// the faces to settle.
std::string check(const GaussSeidelSettings& settings)
{
  if (!(settings.relaxation > 0.0 && settings.relaxation <= 1.0))
    return refusal("relaxation", "in (0,1]", settings.relaxation);
  if (!(settings.over_relaxation >= 1.0 && settings.over_relaxation < 2.0))
    return refusal("over_relaxation", "in [1,2)", settings.over_relaxation);
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
  std::string problem = check_stopping(settings_);
  if (problem.empty()) problem = check(settings_.gauss_seidel);
  if (!problem.empty()) throw std::invalid_argument(problem);
}

SolveReport GaussSeidel::solve(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                               SweepExchange* exchange, JoiningContacts* joining)
{
  // Without an exchange and without contacts there is nothing to do unless some join (a
  // problem without contacts has converged); with an exchange, every rank takes part in every
  // sweep's exchange, contacts or not.
  if (contacts.empty() && !exchange && !(joining && joining->join(true))) return {};
  return settings_.gauss_seidel.full_sweep_every > 1 ? solve_in_cycles(contacts, velocity, exchange, joining)
                                                     : solve_in_full_sweeps(contacts, velocity, exchange, joining);
}

SolveReport solve_gauss_seidel(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                               const SolverSettings& settings, SweepExchange* exchange, JoiningContacts* joining)
{
  return GaussSeidel(settings).solve(contacts, velocity, exchange, joining);
}

}  // namespace cd
