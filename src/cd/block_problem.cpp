// The block's problem and its complementarity form (cd/block_problem.h).
#include "cd/block_problem.h"

#include <algorithm>
#include <cmath>

namespace cd {

Local2 BlockProblem::velocity(std::size_t i, const std::vector<Local2>& p) const
{
  const std::size_t m = size();
  Local2 u{u0[i], u0[m + i]};
  for (std::size_t j = 0; j < m; j++) {
    u.n += nn(i, j) * p[j].n + nt(i, j) * p[j].t;
    u.t += tn(i, j) * p[j].n + tt(i, j) * p[j].t;
  }
  return u;
}

double BlockProblem::velocity_scale() const
{
  double scale = 0.0;
  for (const double u : u0) scale = std::max(scale, std::fabs(u));
  return scale;
}

BlockLcp to_lcp(const BlockProblem& problem)
{
  const std::size_t m = problem.size(), n = 4 * m;
  BlockLcp lcp{std::vector<double>(n * n, 0.0), std::vector<double>(n, 0.0)};
  const auto cell = [&](std::size_t row, std::size_t column) -> double& { return lcp.M[row * n + column]; };
  for (std::size_t i = 0; i < m; i++) {
    for (std::size_t j = 0; j < m; j++) {
      const double wnn = problem.nn(i, j), wnt = problem.nt(i, j), wtn = problem.tn(i, j), wtt = problem.tt(i, j);
      cell(i, j) = wnn, cell(i, m + j) = wnt, cell(i, 2 * m + j) = -wnt;
      cell(m + i, j) = wtn, cell(m + i, m + j) = wtt, cell(m + i, 2 * m + j) = -wtt;
      cell(2 * m + i, j) = -wtn, cell(2 * m + i, m + j) = -wtt, cell(2 * m + i, 2 * m + j) = wtt;
    }
    cell(m + i, 3 * m + i) = 1.0;
    cell(2 * m + i, 3 * m + i) = 1.0;
    cell(3 * m + i, i) = problem.mu[i], cell(3 * m + i, m + i) = -1.0, cell(3 * m + i, 2 * m + i) = -1.0;
    lcp.q[i] = problem.u0[i], lcp.q[m + i] = problem.u0[m + i], lcp.q[2 * m + i] = -problem.u0[m + i];
  }
  return lcp;
}

std::vector<Local2> impulses_from_lcp(const std::vector<double>& z, std::size_t m)
{
  std::vector<Local2> p(m);
  for (std::size_t i = 0; i < m; i++) p[i] = {z[i], std::max(z[m + i], 0.0) - std::max(z[2 * m + i], 0.0)};
  return p;
}

}  // namespace cd
