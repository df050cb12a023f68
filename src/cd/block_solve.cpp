// The exact block solve (cd/block_solve.h).
#include "cd/block_solve.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <unordered_map>
#include <utility>

#include "cd/friction_states.h"
#include "cd/lemke.h"

namespace cd {

namespace {

// The block's velocities' response: W_ij (2x2, u_i per unit p_j) for the block's contacts i, j
// that share a mobile body, kept as four dense m x m arrays.
struct BlockDelassus {
  std::size_t m = 0;
  std::vector<double> nn, nt, tn, tt;  // row i, column j: d u_i{n,t} / d p_j{n,t}
  double& at(std::vector<double>& part, std::size_t i, std::size_t j) { return part[i * m + j]; }
};

BlockDelassus block_delassus(const std::vector<Contact>& contacts, const std::vector<int>& block)
{
  BlockDelassus w;
  w.m = block.size();
  for (auto* part : {&w.nn, &w.nt, &w.tn, &w.tt}) part->assign(w.m * w.m, 0.0);
  std::unordered_map<int, std::vector<std::size_t>> touching;  // mobile body -> block contacts
  for (std::size_t i = 0; i < w.m; i++)
    for (const int body : {contacts[block[i]].body_a, contacts[block[i]].body_b})
      if (body != 0) touching[body].push_back(i);
  for (std::size_t j = 0; j < w.m; j++) {
    const Contact& cj = contacts[block[j]];
    for (const int body : {cj.body_a, cj.body_b}) {
      if (body == 0) continue;
      const BodyVelocity by_n = impulse_response(cj, {1.0, 0.0}, body), by_t = impulse_response(cj, {0.0, 1.0}, body);
      for (const std::size_t i : touching[body]) {
        const Contact& ci = contacts[block[i]];
        const bool on_a = ci.body_a == body;
        const BodyVelocity zero{};
        const Local2 un = relative_velocity(ci, on_a ? by_n : zero, on_a ? zero : by_n);
        const Local2 ut = relative_velocity(ci, on_a ? by_t : zero, on_a ? zero : by_t);
        w.at(w.nn, i, j) += un.n;
        w.at(w.tn, i, j) += un.t;
        w.at(w.nt, i, j) += ut.n;
        w.at(w.tt, i, j) += ut.t;
      }
    }
  }
  return w;
}

// A cluster with a loop of contacts is hyperstatic: its impulses are fixed only up to a
// self-stress that moves nothing, and Lemke's path may end anywhere along it. The block's law
// therefore acts on u + rho (p - p_k), rho = proximal W_ii per contact and p_k the impulses before
// the block solve: W + rho is positive definite, the answer unique, and of the block's solutions
// (rho -> 0) the one nearest p_k. Without it a 10 s chute at mu 2, 28 deg grew a self-stress of
// 1e7 times the impulses' scale at its 1700th block solve, which fooled the stopping norm from
// then on (doc/stalls.md); 1e-4 converges the corpus as the exact solve does, 1e-2 leaves 3 of
// 112 steps at the cap.
constexpr double proximal = 1e-4;

}  // namespace

BlockProblem block_problem(const std::vector<Contact>& contacts, const std::vector<BodyVelocity>& velocity,
                           const std::vector<int>& block)
{
  BlockDelassus w = block_delassus(contacts, block);
  const std::size_t m = w.m;
  std::vector<double> W(4 * m * m), u0(2 * m), mu(m);
  const auto response = [&](std::size_t row, std::size_t column) -> double& { return W[row * 2 * m + column]; };
  for (std::size_t i = 0; i < m; i++) {
    const Contact& ci = contacts[block[i]];
    Local2 affine = law_velocity(ci, velocity[ci.body_a], velocity[ci.body_b]);
    for (std::size_t j = 0; j < m; j++) {
      const Local2 pj = contacts[block[j]].impulse;
      const double wnn = w.at(w.nn, i, j), wnt = w.at(w.nt, i, j), wtn = w.at(w.tn, i, j), wtt = w.at(w.tt, i, j);
      affine.n -= wnn * pj.n + wnt * pj.t;
      affine.t -= wtn * pj.n + wtt * pj.t;
      response(i, j) = wnn, response(i, m + j) = wnt, response(m + i, j) = wtn, response(m + i, m + j) = wtt;
    }
    const double rho_n = proximal * ci.delassus.nn, rho_t = proximal * ci.delassus.tt;
    affine.n -= rho_n * ci.impulse.n;
    affine.t -= rho_t * ci.impulse.t;
    response(i, i) += rho_n;
    response(m + i, m + i) += rho_t;
    u0[i] = affine.n, u0[m + i] = affine.t;
    mu[i] = ci.mu;
  }
  return {std::move(W), std::move(u0), std::move(mu)};
}

namespace {

// An answer whose impulses still exceed this many times the cluster's scale (its largest
// impulse before, or the largest impulse change a local solve would make, |W_ii^-1 u|) is refused.
constexpr double largest_impulse_growth = 100.0;

double impulse_size(Local2 p)
{
  return std::hypot(p.n, p.t);
}

// Lemke's impulses put on the Coulomb cone: its round-off may leave a contact with p_n = 0 a
// tangential impulse (1e-13 against a cluster's 1e-6 was seen), which a sweep takes off and the
// next solve of the same block puts back; a kept block solved every few sweeps then holds the
// norm at that cycle's size (5e-9 on the 2-rank test cell, where the tolerance was 1e-12).
Local2 on_cone(double p_n, double p_t, double mu)
{
  const double normal = std::max(p_n, 0.0);
  return {normal, std::clamp(p_t, -mu * normal, mu * normal)};
}

// The cluster's scale for largest_impulse_growth.
double cluster_scale(const std::vector<Contact>& contacts, const std::vector<BodyVelocity>& velocity,
                     const std::vector<int>& block)
{
  double scale = 0.0;
  for (const int k : block) {
    const Contact& c = contacts[k];
    const Local2 u = law_velocity(c, velocity[c.body_a], velocity[c.body_b]);
    const Local2 stop{c.delassus.inverse_nn * u.n, c.delassus.inverse_tt * u.t};
    scale = std::max({scale, impulse_size(c.impulse), impulse_size(stop)});
  }
  return scale;
}

// The cluster's problem solved by its contacts' states, from those the sweeps left (the fast
// path: cd/friction_states.h); true if that ended.
bool solved_by_states(const std::vector<Contact>& contacts, const std::vector<int>& block, const BlockProblem& problem,
                      std::vector<Local2>& answer)
{
  constexpr int max_solves = 12, max_rounds = 4;
  std::vector<FrictionState> states(block.size());
  for (std::size_t i = 0; i < block.size(); i++) states[i] = state_of(contacts[block[i]].impulse, problem.mu[i]);
  StatesSolve solve = solve_by_states(problem, std::move(states), max_solves);
  if (!solve.solved && std::find(solve.changed.begin(), solve.changed.end(), true) != solve.changed.end())
    solve = solve_cycling_by_lemke(problem, solve.states, solve.changed, max_rounds);
  if (solve.solved) answer = std::move(solve.answer);
  return solve.solved;
}

// The cluster's complementarity problem solved by Lemke; true if it ended at a solution.
bool solved_by_lemke(const BlockProblem& problem, std::vector<Local2>& answer, int& pivots)
{
  const BlockLcp lcp = to_lcp(problem);
  const std::size_t n = lcp.q.size();
  std::vector<double> z;
  const LemkeResult lemke = solve_lcp_lemke(lcp.M, lcp.q, z, static_cast<int>(10 * n + 100));
  pivots += lemke.pivots;
  if (!lemke.solved) return false;
  answer = impulses_from_lcp(z, problem.size());
  return true;
}

// One cluster's LCP (cd/block_solve.h) solved by its contacts' states, or else by Lemke; true if
// it was and its answer holds no runaway self-stress, and then its impulses and the velocities
// are changed.
bool solve_cluster(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, const std::vector<int>& block,
                   int& pivots)
{
  const BlockProblem problem = block_problem(contacts, velocity, block);
  const std::size_t m = block.size();
  std::vector<Local2> answer;
  if (!solved_by_states(contacts, block, problem, answer) && !solved_by_lemke(problem, answer, pivots)) return false;
  const double limit = largest_impulse_growth * cluster_scale(contacts, velocity, block);
  for (std::size_t i = 0; i < m; i++) answer[i] = on_cone(answer[i].n, answer[i].t, contacts[block[i]].mu);
  for (const Local2& p : answer)
    if (!(impulse_size(p) <= limit)) return false;
  for (std::size_t i = 0; i < m; i++) {
    Contact& c = contacts[block[i]];
    apply_impulse(c, {answer[i].n - c.impulse.n, answer[i].t - c.impulse.t}, velocity[c.body_a], velocity[c.body_b]);
    c.impulse = answer[i];
    c.direction = {};
  }
  return true;
}

// The block split into clusters: contacts linked through shared mobile bodies.
std::vector<std::vector<int>> clusters_of(const std::vector<Contact>& contacts, const std::vector<int>& block)
{
  std::unordered_map<int, int> parent;  // mobile body -> a body of its cluster
  const auto root = [&](int body) {
    if (!parent.count(body)) parent[body] = body;
    while (parent[body] != body) body = parent[body] = parent[parent[body]];
    return body;
  };
  for (const int k : block) {
    const Contact& c = contacts[k];
    if (c.body_a != 0 && c.body_b != 0) parent[root(c.body_a)] = root(c.body_b);
  }
  std::unordered_map<int, std::size_t> cluster_of_root;
  std::vector<std::vector<int>> clusters;
  for (const int k : block) {
    const int body = contacts[k].body_a != 0 ? contacts[k].body_a : contacts[k].body_b;
    const auto [place, added] = cluster_of_root.emplace(body != 0 ? root(body) : -k - 1, clusters.size());
    if (added) clusters.emplace_back();
    clusters[place->second].push_back(k);
  }
  return clusters;
}

}  // namespace

BlockSolve solve_block(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                       const std::vector<int>& block)
{
  BlockSolve result;
  for (const std::vector<int>& cluster : clusters_of(contacts, block)) {
    ++result.clusters;
    if (!solve_cluster(contacts, velocity, cluster, result.pivots)) ++result.unsolved;
  }
  return result;
}

std::vector<int> residual_carriers(const std::vector<Contact>& contacts, const std::vector<BodyVelocity>& velocity,
                                   double share, int max_count)
{
  std::vector<std::pair<double, int>> residual(contacts.size());
  double total = 0.0;
  for (std::size_t k = 0; k < contacts.size(); k++) {
    const Contact& c = contacts[k];
    const Local2 u = law_velocity(c, velocity[c.body_a], velocity[c.body_b]);
    const double w = c.delassus.nn;
    residual[k] = {natural_map_residual_squared({w * c.impulse.n, w * c.impulse.t}, u, c.mu), static_cast<int>(k)};
    total += residual[k].first;
  }
  std::sort(residual.begin(), residual.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<int> carriers;
  double sum = 0.0;
  for (std::size_t k = 0; k < residual.size() && sum < share * total && static_cast<int>(carriers.size()) < max_count;
       k++) {
    sum += residual[k].first;
    carriers.push_back(residual[k].second);
  }
  return carriers;
}

int block_budget(int sweeps, std::size_t contact_count, int seeds)
{
  constexpr int largest_block = 200;
  const double work_budget = std::cbrt(static_cast<double>(sweeps) * static_cast<double>(contact_count));
  return std::clamp(static_cast<int>(work_budget), seeds, std::max(seeds, largest_block));
}

std::vector<int> block_around(const std::vector<Contact>& contacts, int body_count, const std::vector<int>& seeds,
                              int hops, int max_size)
{
  std::vector<std::vector<int>> touching(static_cast<std::size_t>(body_count));
  for (std::size_t k = 0; k < contacts.size(); k++)
    for (const int body : {contacts[k].body_a, contacts[k].body_b})
      if (body != 0) touching[body].push_back(static_cast<int>(k));
  std::vector<char> taken(contacts.size(), 0);
  std::vector<int> block, frontier;
  for (const int s : seeds)
    if (!taken[s] && static_cast<int>(block.size()) < max_size) taken[s] = 1, block.push_back(s), frontier.push_back(s);
  for (int hop = 0; hop < hops && !frontier.empty(); hop++) {
    std::vector<int> next;
    for (const int k : frontier)
      for (const int body : {contacts[k].body_a, contacts[k].body_b})
        if (body != 0)
          for (const int other : touching[body])
            if (!taken[other] && static_cast<int>(block.size()) < max_size)
              taken[other] = 1, block.push_back(other), next.push_back(other);
    frontier.swap(next);
  }
  std::sort(block.begin(), block.end());
  return block;
}

}  // namespace cd
