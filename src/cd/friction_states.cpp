// The block solve by contact states (cd/friction_states.h).
#include "cd/friction_states.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include "cd/dense_solve.h"
#include "cd/lemke.h"

namespace cd {

namespace {

// The floors of the checks, as fractions of the impulses' and the velocities' scales: a solve's
// answer meets its own equations to equation_floor, and the law to law_floor.
constexpr double equation_floor = 1e-8;
constexpr double law_floor = 1e-10;

double impulse_scale(const std::vector<Local2>& p)
{
  double scale = 0.0;
  for (const Local2& pi : p) scale = std::max({scale, std::fabs(pi.n), std::fabs(pi.t)});
  return scale;
}

double slide_sign(FrictionState state)
{
  return state == FrictionState::slide_positive ? 1.0 : -1.0;
}

// The unknowns the states of the held contacts fix: p_n of each closed one, p_t of each sticking
// one (a sliding one's p_t is ±mu p_n); -1 where a contact has none.
struct HeldUnknowns {
  std::vector<std::ptrdiff_t> normal, tangent;
  std::size_t count = 0;

  HeldUnknowns(const std::vector<FrictionState>& states, const std::vector<bool>& held)
      : normal(states.size(), -1), tangent(states.size(), -1)
  {
    for (std::size_t i = 0; i < states.size(); i++) {
      if (!held[i] || states[i] == FrictionState::open) continue;
      normal[i] = static_cast<std::ptrdiff_t>(count++);
      if (states[i] == FrictionState::stick) tangent[i] = static_cast<std::ptrdiff_t>(count++);
    }
  }
  // Adds to `row` (count entries) what each unknown does to contact i's normal (or tangential)
  // velocity.
  void add_response(const BlockProblem& w, const std::vector<double>& mu, const std::vector<FrictionState>& states,
                    std::size_t i, bool tangential, double* row) const
  {
    for (std::size_t j = 0; j < normal.size(); j++) {
      if (normal[j] < 0) continue;
      const double by_n = tangential ? w.tn(i, j) : w.nn(i, j), by_t = tangential ? w.tt(i, j) : w.nt(i, j);
      if (tangent[j] >= 0) {
        row[normal[j]] += by_n;
        row[tangent[j]] += by_t;
      } else {
        row[normal[j]] += by_n + by_t * slide_sign(states[j]) * mu[j];
      }
    }
  }
  // The held contacts' impulses from the unknowns x.
  void impulses(const std::vector<FrictionState>& states, const std::vector<double>& mu, const double* x,
                std::vector<Local2>& p) const
  {
    for (std::size_t i = 0; i < normal.size(); i++) {
      if (normal[i] < 0) continue;
      p[i].n = x[normal[i]];
      p[i].t = tangent[i] >= 0 ? x[tangent[i]] : slide_sign(states[i]) * mu[i] * p[i].n;
    }
  }
};

// The impulses the states fix (every contact held); false if their system is singular.
bool impulses_of_states(const BlockProblem& w, const std::vector<double>& mu, const std::vector<FrictionState>& states,
                        std::vector<Local2>& p)
{
  const std::size_t m = w.size();
  const HeldUnknowns unknowns(states, std::vector<bool>(m, true));
  const std::size_t k = unknowns.count;
  std::vector<double> A(k * k, 0.0), b(k, 0.0);
  for (std::size_t i = 0; i < m; i++)
    for (const bool tangential : {false, true}) {
      const std::ptrdiff_t row = tangential ? unknowns.tangent[i] : unknowns.normal[i];
      if (row < 0) continue;
      b[static_cast<std::size_t>(row)] = -(tangential ? w.u0[m + i] : w.u0[i]);
      unknowns.add_response(w, mu, states, i, tangential, &A[static_cast<std::size_t>(row) * k]);
    }
  if (!solve_dense(A, b, k)) return false;
  p.assign(m, Local2{});
  unknowns.impulses(states, mu, b.data(), p);
  return true;
}

// The state the law wants for contact i at impulse p and velocity u, `state` if it holds.
FrictionState checked_state(FrictionState state, Local2 p, Local2 u, double mu, double p_floor, double u_floor)
{
  switch (state) {
    case FrictionState::open:
      // Closing, it slides against its tangential velocity unless it has none.
      if (!(u.n < -u_floor)) return state;
      if (std::fabs(u.t) <= u_floor) return FrictionState::stick;
      return u.t > 0.0 ? FrictionState::slide_negative : FrictionState::slide_positive;
    case FrictionState::stick:
      if (p.n < -p_floor) return FrictionState::open;
      if (std::fabs(p.t) > mu * p.n + p_floor)
        return p.t > 0.0 ? FrictionState::slide_positive : FrictionState::slide_negative;
      return state;
    default:
      if (p.n < -p_floor) return FrictionState::open;
      // Friction opposes the slip: p_t = +mu p_n slides with u_t <= 0.
      if (slide_sign(state) * u.t > u_floor) return FrictionState::stick;
      return state;
  }
}

// The velocities a solve of the states' system leaves: u_n = 0 where closed, u_t = 0 where
// sticking, to `floor`; an ill-conditioned system that misses them is no answer.
bool meets_its_equations(FrictionState state, Local2 u, double floor)
{
  if (state == FrictionState::open) return true;
  if (!(std::fabs(u.n) <= floor)) return false;
  return state != FrictionState::stick || std::fabs(u.t) <= floor;
}

}  // namespace

FrictionState state_of(Local2 impulse, double mu)
{
  constexpr double on_edge = 1.0 - 1e-9;
  if (!(impulse.n > 0.0)) return FrictionState::open;
  if (std::fabs(impulse.t) >= on_edge * mu * impulse.n)
    return impulse.t > 0.0 ? FrictionState::slide_positive : FrictionState::slide_negative;
  return FrictionState::stick;
}

StatesSolve solve_by_states(const BlockProblem& problem, std::vector<FrictionState> states, int max_solves)
{
  constexpr int patience = 3;  // solves without fewer contacts in a wrong state
  const std::vector<double>& mu = problem.mu;
  const std::size_t m = mu.size();
  const BlockProblem& w = problem;
  const double u_scale = w.velocity_scale();
  StatesSolve result;
  result.changed.assign(m, false);
  std::size_t fewest = m + 1;
  int without_progress = 0;
  std::vector<Local2> p;
  while (result.solves < max_solves) {
    ++result.solves;
    result.states = states;
    if (!impulses_of_states(w, mu, states, p)) return result;
    const double p_floor = law_floor * impulse_scale(p), u_floor = law_floor * u_scale;
    std::size_t wrong = 0;
    std::vector<FrictionState> next(states);
    for (std::size_t i = 0; i < m; i++) {
      const Local2 u = w.velocity(i, p);
      if (!meets_its_equations(states[i], u, equation_floor * u_scale)) return result;
      next[i] = checked_state(states[i], p[i], u, mu[i], p_floor, u_floor);
      wrong += next[i] != states[i];
      if (next[i] != states[i]) result.changed[i] = true;
    }
    if (wrong == 0) {
      result.solved = true;
      result.answer = std::move(p);
      return result;
    }
    if (wrong < fewest) fewest = wrong, without_progress = 0;
    else ++without_progress;
    if (without_progress < patience) {
      states = std::move(next);
      continue;
    }
    // Whole-set changes cycle: change one contact in a wrong state, a different one each time.
    std::vector<std::size_t> changed;
    for (std::size_t i = 0; i < m; i++)
      if (next[i] != states[i]) changed.push_back(i);
    const std::size_t pick = changed[static_cast<std::size_t>(result.solves * 7919) % changed.size()];
    states[pick] = next[pick];
  }
  return result;
}

StatesSolve solve_cycling_by_lemke(const BlockProblem& problem, const std::vector<FrictionState>& states,
                                   std::vector<bool> cycling, int max_rounds)
{
  const std::vector<double>& mu = problem.mu;
  const std::size_t m = mu.size();
  const BlockProblem& w = problem;
  const double u_scale = w.velocity_scale();
  StatesSolve result;
  result.states = states;
  for (int round = 0; round < max_rounds; round++) {
    ++result.solves;
    std::vector<std::size_t> free;  // the cycling contacts, in order
    std::vector<bool> held(m);
    for (std::size_t i = 0; i < m; i++) {
      held[i] = !cycling[i];
      if (cycling[i]) free.push_back(i);
    }
    const std::size_t c = free.size(), columns = 1 + 2 * c;
    const HeldUnknowns unknowns(states, held);
    const std::size_t k = unknowns.count;
    // The held unknowns as affine in the free impulses: X = X_0 + sum over free (p_n, p_t) X_a.
    std::vector<double> A(k * k, 0.0), X(k * columns, 0.0);
    for (std::size_t i = 0; i < m; i++)
      for (const bool tangential : {false, true}) {
        const std::ptrdiff_t at = tangential ? unknowns.tangent[i] : unknowns.normal[i];
        if (at < 0) continue;
        const std::size_t row = static_cast<std::size_t>(at);
        unknowns.add_response(w, mu, states, i, tangential, &A[row * k]);
        X[row * columns] = -(tangential ? w.u0[m + i] : w.u0[i]);
        for (std::size_t a = 0; a < c; a++) {
          X[row * columns + 1 + a] = -(tangential ? w.tn(i, free[a]) : w.nn(i, free[a]));
          X[row * columns + 1 + c + a] = -(tangential ? w.tt(i, free[a]) : w.nt(i, free[a]));
        }
      }
    if (!solve_dense(A, X, k, columns)) return result;
    // The free contacts' response with the held ones following: u0 and W over (p_n..., p_t...).
    std::vector<double> u0(2 * c), W(4 * c * c), along(k);
    for (std::size_t b = 0; b < 2 * c; b++) {
      const std::size_t i = free[b % c];
      const bool tangential = b >= c;
      std::fill(along.begin(), along.end(), 0.0);
      unknowns.add_response(w, mu, states, i, tangential, along.data());
      for (std::size_t col = 0; col < columns; col++) {
        double sum = 0.0;
        for (std::size_t v = 0; v < k; v++) sum += along[v] * X[v * columns + col];
        if (col == 0) {
          u0[b] = (tangential ? w.u0[m + i] : w.u0[i]) + sum;
          continue;
        }
        const std::size_t a = (col - 1) % c;
        const bool by_tangential = col - 1 >= c;
        const double direct = tangential ? (by_tangential ? w.tt(i, free[a]) : w.tn(i, free[a]))
                                         : (by_tangential ? w.nt(i, free[a]) : w.nn(i, free[a]));
        W[b * 2 * c + (col - 1)] = direct + sum;
      }
    }
    std::vector<double> free_mu(c), z;
    for (std::size_t a = 0; a < c; a++) free_mu[a] = mu[free[a]];
    const BlockLcp reduced = to_lcp({std::move(W), std::move(u0), std::move(free_mu)});
    if (!solve_lcp_lemke(reduced.M, reduced.q, z, static_cast<int>(40 * c + 100)).solved) return result;
    const std::vector<Local2> free_impulses = impulses_from_lcp(z, c);
    std::vector<Local2> p(m);
    std::vector<double> free_p(columns, 1.0), x(k, 0.0);
    for (std::size_t a = 0; a < c; a++) {
      p[free[a]] = free_impulses[a];
      free_p[1 + a] = p[free[a]].n;
      free_p[1 + c + a] = p[free[a]].t;
    }
    for (std::size_t v = 0; v < k; v++)
      for (std::size_t col = 0; col < columns; col++) x[v] += X[v * columns + col] * free_p[col];
    unknowns.impulses(states, mu, x.data(), p);
    const double p_floor = law_floor * impulse_scale(p), u_floor = law_floor * u_scale;
    bool held_hold = true;
    for (std::size_t i = 0; i < m; i++) {
      if (cycling[i]) continue;
      const Local2 u = w.velocity(i, p);
      if (!meets_its_equations(states[i], u, equation_floor * u_scale)) return result;
      if (checked_state(states[i], p[i], u, mu[i], p_floor, u_floor) != states[i]) {
        cycling[i] = true;
        held_hold = false;
      }
    }
    if (held_hold) {
      result.solved = true;
      result.answer = std::move(p);
      return result;
    }
  }
  return result;
}

}  // namespace cd
