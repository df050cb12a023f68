// The block solve by contact states (cd/friction_states.h).
#include "cd/friction_states.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

namespace cd {

namespace {

// Solves A x = b (A k x k, row-major, overwritten; x in b) by LU with partial pivoting; false if
// a pivot falls below 1e-13 of A's largest entry.
bool solve_dense(std::vector<double>& A, std::vector<double>& b, std::size_t k)
{
  double largest = 0.0;
  for (const double a : A) largest = std::max(largest, std::fabs(a));
  const double singular = 1e-13 * largest;
  for (std::size_t col = 0; col < k; col++) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < k; r++)
      if (std::fabs(A[r * k + col]) > std::fabs(A[pivot * k + col])) pivot = r;
    if (!(std::fabs(A[pivot * k + col]) > singular)) return false;
    if (pivot != col) {
      for (std::size_t c = 0; c < k; c++) std::swap(A[pivot * k + c], A[col * k + c]);
      std::swap(b[pivot], b[col]);
    }
    const double* top = &A[col * k];
    for (std::size_t r = col + 1; r < k; r++) {
      double* row = &A[r * k];
      const double factor = row[col] / top[col];
      if (factor == 0.0) continue;
      for (std::size_t c = col + 1; c < k; c++) row[c] -= factor * top[c];
      b[r] -= factor * b[col];
    }
  }
  for (std::size_t col = k; col-- > 0;) {
    double sum = b[col];
    for (std::size_t c = col + 1; c < k; c++) sum -= A[col * k + c] * b[c];
    b[col] = sum / A[col * k + col];
  }
  return true;
}

// The block's response u = q + W p read from the complementarity layout: W_nn, W_nt, W_tn, W_tt.
struct Response {
  const std::vector<double>& M;
  const std::vector<double>& q;
  std::size_t m;

  double nn(std::size_t i, std::size_t j) const { return M[i * 4 * m + j]; }
  double nt(std::size_t i, std::size_t j) const { return M[i * 4 * m + m + j]; }
  double tn(std::size_t i, std::size_t j) const { return M[(m + i) * 4 * m + j]; }
  double tt(std::size_t i, std::size_t j) const { return M[(m + i) * 4 * m + m + j]; }
  Local2 velocity(std::size_t i, const std::vector<Local2>& p) const
  {
    Local2 u{q[i], q[m + i]};
    for (std::size_t j = 0; j < m; j++) {
      u.n += nn(i, j) * p[j].n + nt(i, j) * p[j].t;
      u.t += tn(i, j) * p[j].n + tt(i, j) * p[j].t;
    }
    return u;
  }
};

double slide_sign(FrictionState state)
{
  return state == FrictionState::slide_positive ? 1.0 : -1.0;
}

// The impulses the states fix: unknowns p_n of the closed contacts and p_t of the sticking
// ones; false if their system is singular.
bool impulses_of_states(const Response& w, const std::vector<double>& mu, const std::vector<FrictionState>& states,
                        std::vector<Local2>& p)
{
  const std::size_t m = w.m;
  std::vector<std::ptrdiff_t> normal(m, -1), tangent(m, -1);
  std::size_t k = 0;
  for (std::size_t i = 0; i < m; i++) {
    if (states[i] == FrictionState::open) continue;
    normal[i] = static_cast<std::ptrdiff_t>(k++);
    if (states[i] == FrictionState::stick) tangent[i] = static_cast<std::ptrdiff_t>(k++);
  }
  std::vector<double> A(k * k, 0.0), b(k, 0.0);
  // Row `row` of the system: contact i's normal (or tangential) velocity = 0.
  const auto fill_row = [&](std::size_t row, std::size_t i, bool tangential) {
    b[row] = -(tangential ? w.q[m + i] : w.q[i]);
    for (std::size_t j = 0; j < m; j++) {
      if (normal[j] < 0) continue;
      const double by_n = tangential ? w.tn(i, j) : w.nn(i, j), by_t = tangential ? w.tt(i, j) : w.nt(i, j);
      if (tangent[j] >= 0) {
        A[row * k + static_cast<std::size_t>(normal[j])] += by_n;
        A[row * k + static_cast<std::size_t>(tangent[j])] += by_t;
      } else {
        A[row * k + static_cast<std::size_t>(normal[j])] += by_n + by_t * slide_sign(states[j]) * mu[j];
      }
    }
  };
  for (std::size_t i = 0; i < m; i++) {
    if (normal[i] >= 0) fill_row(static_cast<std::size_t>(normal[i]), i, false);
    if (tangent[i] >= 0) fill_row(static_cast<std::size_t>(tangent[i]), i, true);
  }
  if (!solve_dense(A, b, k)) return false;
  p.assign(m, Local2{});
  for (std::size_t i = 0; i < m; i++) {
    if (normal[i] < 0) continue;
    p[i].n = b[static_cast<std::size_t>(normal[i])];
    p[i].t = tangent[i] >= 0 ? b[static_cast<std::size_t>(tangent[i])] : slide_sign(states[i]) * mu[i] * p[i].n;
  }
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

StatesSolve solve_by_states(const std::vector<double>& M, const std::vector<double>& q, const std::vector<double>& mu,
                            std::vector<FrictionState> states, int max_solves)
{
  constexpr int patience = 3;           // solves without fewer contacts in a wrong state
  constexpr double solve_floor = 1e-8;  // of the velocities' scale: the system's equations met
  const std::size_t m = mu.size();
  const Response w{M, q, m};
  double u_scale = 0.0;
  for (std::size_t i = 0; i < 2 * m; i++) u_scale = std::max(u_scale, std::fabs(q[i]));
  StatesSolve result;
  std::size_t fewest = m + 1;
  int without_progress = 0;
  std::vector<Local2> p;
  while (result.solves < max_solves) {
    ++result.solves;
    if (!impulses_of_states(w, mu, states, p)) return result;
    double p_scale = 0.0;
    for (const Local2& pi : p) p_scale = std::max({p_scale, std::fabs(pi.n), std::fabs(pi.t)});
    const double p_floor = 1e-10 * p_scale, u_floor = 1e-10 * u_scale;
    std::size_t wrong = 0;
    std::vector<FrictionState> next(states);
    for (std::size_t i = 0; i < m; i++) {
      const Local2 u = w.velocity(i, p);
      if (!meets_its_equations(states[i], u, solve_floor * u_scale)) return result;
      next[i] = checked_state(states[i], p[i], u, mu[i], p_floor, u_floor);
      wrong += next[i] != states[i];
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

}  // namespace cd
