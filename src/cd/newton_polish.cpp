// The contacts' semismooth Newton method and Gauss–Seidel's polish made of it (cd/newton_polish.h).
#include "cd/newton_polish.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace cd {

namespace {

// d u_i / d p_j of two contacts sharing a mobile body (m/s per N s).
struct Block2 {
  double nn = 0.0, nt = 0.0, tn = 0.0, tt = 0.0;
};

// W + rho by rows: contact i's neighbours j (itself first) and their blocks.
struct SparseDelassus {
  std::vector<std::vector<std::pair<int, Block2>>> rows;

  Block2& at(int i, int j)
  {
    for (auto& entry : rows[i])
      if (entry.first == j) return entry.second;
    rows[i].push_back({j, Block2{}});
    return rows[i].back().second;
  }
};

SparseDelassus sparse_delassus(const std::vector<Contact>& contacts, std::size_t body_count)
{
  const int n = static_cast<int>(contacts.size());
  SparseDelassus w;
  w.rows.resize(n);
  std::vector<std::vector<int>> touching(body_count);  // mobile body -> its contacts
  for (int i = 0; i < n; i++) {
    w.at(i, i) = {};
    for (const int body : {contacts[i].body_a, contacts[i].body_b})
      if (body != 0) touching[body].push_back(i);
  }
  for (int j = 0; j < n; j++) {
    const Contact& cj = contacts[j];
    for (const int body : {cj.body_a, cj.body_b}) {
      if (body == 0) continue;
      const BodyVelocity by_n = impulse_response(cj, {1.0, 0.0}, body), by_t = impulse_response(cj, {0.0, 1.0}, body);
      const BodyVelocity zero{};
      for (const int i : touching[body]) {
        const Contact& ci = contacts[i];
        const bool on_a = ci.body_a == body;
        const Local2 un = relative_velocity(ci, on_a ? by_n : zero, on_a ? zero : by_n);
        const Local2 ut = relative_velocity(ci, on_a ? by_t : zero, on_a ? zero : by_t);
        Block2& block = w.at(i, j);
        block.nn += un.n, block.tn += un.t, block.nt += ut.n, block.tt += ut.t;
      }
    }
  }
  return w;
}

// The problem u = u_k + W (p - p_k) over every contact; p as (p_n, p_t) of each in turn.
struct Problem {
  const std::vector<Contact>& contacts;
  SparseDelassus w;
  std::vector<double> u_start, p_start;  // u_k, p_k
  double proximal = 0.0;                 // the Jacobian's W_ii + proximal W_ii

  std::size_t size() const { return 2 * contacts.size(); }
};

// Fischer–Burmeister's function of one complementarity pair, a >= 0, b >= 0, a b = 0 at its zeros,
// and its partial derivatives (at a = b = 0 one element of the generalized gradient).
struct FischerBurmeister {
  double value = 0.0, by_a = 0.0, by_b = 0.0;
};
FischerBurmeister fischer_burmeister(double a, double b)
{
  const double root = std::hypot(a, b);
  if (!(root > 0.0)) return {0.0, 1.0 - M_SQRT1_2, 1.0 - M_SQRT1_2};
  return {a + b - root, 1.0 - a / root, 1.0 - b / root};
}

// A contact's two pairs. With friction, the law is K ∋ p ⊥ û ∈ K*, K the cone |p_t| <= mu p_n
// and û = (u_n + mu |u_t|, u_t) (De Saxcé's); in 2D K is two half-planes and the law two
// scalar pairs on its edges, scaled to m/s by W_nn:
//   W_nn (mu p_n ± p_t) >= 0  ⊥  u_n + 2 mu max(±u_t, 0) >= 0.
// Frictionless: W_nn p_n ⊥ u_n, and W_tt p_t = 0.
struct ContactPairs {
  FischerBurmeister edge[2];  // + then - (the normal pair and p_t = 0 when mu = 0)
  // d max(±u_t, 0) / d u_t: 1 on the side it slides to, 0 on the other, 1/2 each at u_t = 0 (a
  // sweep's sticking answer): with 0 there, p_t would enter no row of its own contact.
  double slides[2];
};

struct Evaluation {
  std::vector<double> u, phi;  // phi: the pairs' FB values (m/s)
  std::vector<ContactPairs> pairs;
  double residual_sq = 0.0;
};

void evaluate(const Problem& problem, const std::vector<double>& p, Evaluation& e)
{
  const std::size_t n = problem.contacts.size();
  e.u.assign(problem.u_start.begin(), problem.u_start.end());
  e.phi.resize(2 * n);
  e.pairs.resize(n);
  e.residual_sq = 0.0;
  for (std::size_t i = 0; i < n; i++) {
    for (const auto& [j, b] : problem.w.rows[i]) {
      const double dn = p[2 * j] - problem.p_start[2 * j], dt = p[2 * j + 1] - problem.p_start[2 * j + 1];
      e.u[2 * i] += b.nn * dn + b.nt * dt;
      e.u[2 * i + 1] += b.tn * dn + b.tt * dt;
    }
    const Contact& c = problem.contacts[i];
    const double u_n = e.u[2 * i], u_t = e.u[2 * i + 1], p_n = p[2 * i], p_t = p[2 * i + 1];
    ContactPairs& pair = e.pairs[i];
    pair.slides[0] = u_t > 0.0 ? 1.0 : u_t < 0.0 ? 0.0 : 0.5;
    pair.slides[1] = 1.0 - pair.slides[0];
    if (c.mu == 0.0) {
      pair.edge[0] = fischer_burmeister(c.delassus.nn * p_n, u_n);
      pair.edge[1] = {c.delassus.tt * p_t, 0.0, 0.0};
    } else {
      const double d = c.delassus.nn;
      pair.edge[0] = fischer_burmeister(d * (c.mu * p_n + p_t), u_n + 2.0 * c.mu * std::max(u_t, 0.0));
      pair.edge[1] = fischer_burmeister(d * (c.mu * p_n - p_t), u_n + 2.0 * c.mu * std::max(-u_t, 0.0));
    }
    e.phi[2 * i] = pair.edge[0].value;
    e.phi[2 * i + 1] = pair.edge[1].value;
    e.residual_sq += e.phi[2 * i] * e.phi[2 * i] + e.phi[2 * i + 1] * e.phi[2 * i + 1];
  }
}

// The generalized Jacobian of the pairs' FB values at the evaluation.
void jacobian(const Problem& problem, const Evaluation& e, Eigen::SparseMatrix<double>& J,
              std::vector<Eigen::Triplet<double>>& entries)
{
  entries.clear();
  for (std::size_t i = 0; i < problem.contacts.size(); i++) {
    const Contact& c = problem.contacts[i];
    const ContactPairs& pair = e.pairs[i];
    const int row_n = static_cast<int>(2 * i), row_t = row_n + 1;
    if (c.mu == 0.0) {
      const FischerBurmeister& normal = pair.edge[0];
      entries.emplace_back(row_n, row_n, (normal.by_a + normal.by_b * problem.proximal) * c.delassus.nn);
      for (const auto& [j, b] : problem.w.rows[i]) {
        entries.emplace_back(row_n, 2 * j, normal.by_b * b.nn);
        entries.emplace_back(row_n, 2 * j + 1, normal.by_b * b.nt);
      }
      entries.emplace_back(row_t, row_t, c.delassus.tt);
      continue;
    }
    for (int side = 0; side < 2; side++) {
      const FischerBurmeister& edge = pair.edge[side];
      const int row = row_n + side;
      const double sign = side == 0 ? 1.0 : -1.0;  // a = W_nn (mu p_n + sign p_t)
      const double d = c.delassus.nn;
      entries.emplace_back(row, row_n, edge.by_a * d * c.mu);
      entries.emplace_back(row, row_t, edge.by_a * d * sign);
      // b = u_n + 2 mu max(sign u_t, 0)
      const double tangential = 2.0 * c.mu * sign * pair.slides[side];
      entries.emplace_back(row, row_n, edge.by_b * problem.proximal * c.delassus.nn);
      entries.emplace_back(row, row_t, edge.by_b * problem.proximal * tangential * c.delassus.tt);
      for (const auto& [j, b] : problem.w.rows[i]) {
        entries.emplace_back(row, 2 * j, edge.by_b * (b.nn + tangential * b.tn));
        entries.emplace_back(row, 2 * j + 1, edge.by_b * (b.nt + tangential * b.tt));
      }
    }
  }
  J.setFromTriplets(entries.begin(), entries.end());  // duplicates summed
}

// The line search's sufficient decrease (Armijo's, on |phi|^2) and its shortest step.
constexpr double sufficient_decrease = 1e-4;
constexpr double shortest_step = 1.0 / 1024.0;
// A step that leaves |phi| above this fraction ends the solve: Newton is not near its fast
// convergence there, and the sweeps go on at less cost.
constexpr double slow_step = 0.5;
// |phi| counts as zero below this fraction of the contacts' velocity scale.
constexpr double round_off = 1e-13;

double velocity_scale(const Problem& problem, const Evaluation& e)
{
  double scale = 0.0;
  for (std::size_t i = 0; i < problem.contacts.size(); i++)
    scale = std::max({scale, std::fabs(e.u[2 * i]), std::fabs(e.u[2 * i + 1]),
                      problem.contacts[i].delassus.nn * std::fabs(problem.p_start[2 * i])});
  return scale;
}

}  // namespace

double alart_curnier_residual_sq(const std::vector<Contact>& contacts, const std::vector<BodyVelocity>& velocity)
{
  double sum = 0.0;
  for (const Contact& c : contacts) {
    const Local2 u = law_velocity(c, velocity[c.body_a], velocity[c.body_b]);
    const Local2 local = solve_coulomb_disk(
        {c.impulse.n - c.delassus.inverse_nn * u.n, c.impulse.t - c.delassus.inverse_tt * u.t}, c.mu);
    const Local2 change = c.delassus.times({c.impulse.n - local.n, c.impulse.t - local.t});
    sum += change.n * change.n + change.t * change.t;
  }
  return sum;
}

NewtonSolve solve_newton(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                         const NewtonSettings& settings)
{
  NewtonSolve solve;
  if (contacts.empty()) return solve;
  Problem problem{contacts, sparse_delassus(contacts, velocity.size()), {}, {}, settings.proximal};
  const std::size_t k = problem.size();
  problem.u_start.resize(k);
  problem.p_start.resize(k);
  for (std::size_t i = 0; i < contacts.size(); i++) {
    const Contact& c = contacts[i];
    const Local2 u = law_velocity(c, velocity[c.body_a], velocity[c.body_b]);
    problem.u_start[2 * i] = u.n, problem.u_start[2 * i + 1] = u.t;
    problem.p_start[2 * i] = c.impulse.n, problem.p_start[2 * i + 1] = c.impulse.t;
  }
  std::vector<double> p = problem.p_start, moved(k);
  Evaluation at, trial;
  evaluate(problem, p, at);
  solve.start = std::sqrt(at.residual_sq);
  Eigen::SparseMatrix<double> J(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(k));
  while (true) {
    const double zero = round_off * velocity_scale(problem, at);
    solve.converged = at.residual_sq <= zero * zero;
    if (solve.converged || solve.iterations >= settings.max_iterations) break;
    jacobian(problem, at, J, entries);
    lu.compute(J);
    if (lu.info() != Eigen::Success) break;
    for (std::size_t row = 0; row < k; row++) rhs[static_cast<Eigen::Index>(row)] = -at.phi[row];
    const Eigen::VectorXd step = lu.solve(rhs);
    ++solve.iterations;
    bool lowered = false;
    for (double length = 1.0; length >= shortest_step && !lowered; length *= 0.5) {
      for (std::size_t row = 0; row < k; row++) moved[row] = p[row] + length * step[static_cast<Eigen::Index>(row)];
      evaluate(problem, moved, trial);
      lowered = trial.residual_sq <= (1.0 - 2.0 * sufficient_decrease * length) * at.residual_sq;
    }
    if (!lowered) break;
    const bool slow = settings.stop_when_slow && trial.residual_sq > slow_step * slow_step * at.residual_sq;
    p.swap(moved);
    std::swap(at, trial);
    if (slow) break;
  }
  solve.residual = std::sqrt(at.residual_sq);
  // The best iterate, on the cone (its round-off may leave it just outside), into the impulses
  // and the velocities.
  for (std::size_t i = 0; i < contacts.size(); i++) {
    Contact& c = contacts[i];
    const double p_n = std::max(p[2 * i], 0.0), bound = c.mu * p_n;
    const Local2 to{p_n, std::clamp(p[2 * i + 1], -bound, bound)};
    if (!std::isfinite(to.n) || !std::isfinite(to.t)) continue;
    apply_impulse(c, {to.n - c.impulse.n, to.t - c.impulse.t}, velocity[c.body_a], velocity[c.body_b]);
    c.impulse = to;
  }
  return solve;
}

NewtonPolish::NewtonPolish(const SolverSettings& settings, SweepExchange* exchange)
    : on_(settings.gauss_seidel.newton_polish && !exchange), start_(std::min(10.0 * settings.tolerance, start_below))
{
}

bool NewtonPolish::act(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report)
{
  if (!on_ || report.iterations < first_after || !(report.residual <= start_) || report.iterations - last_ < wait_)
    return false;
  last_ = report.iterations;
  const double before = alart_curnier_residual_sq(contacts, velocity);
  before_.resize(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); i++) before_[i] = contacts[i].impulse;
  velocity_before_ = velocity;
  const NewtonSolve solve = solve_newton(contacts, velocity, {newton_steps, 1e-4, true});
  report.newton_steps += solve.iterations;
  const double after_sq = alart_curnier_residual_sq(contacts, velocity);
  const bool kept = solve.iterations > 0 && after_sq < kept_below * kept_below * before;
  if (kept) {
    for (Contact& c : contacts) c.direction = {};
  } else {
    for (std::size_t i = 0; i < contacts.size(); i++) contacts[i].impulse = before_[i];
    velocity = velocity_before_;
  }
  wait_ = kept ? every : std::max(2 * wait_, every);
  report.newton_polishes += kept;
  return kept;
}

}  // namespace cd
