// The block's complementarity problem (cd/block_problem.h).
#include "cd/block_problem.h"

#include <cstddef>

namespace cd {

BlockProblem block_lcp(const std::vector<double>& W, const std::vector<double>& u0, const std::vector<double>& mu)
{
  const std::size_t m = mu.size(), n = 4 * m;
  BlockProblem problem{std::vector<double>(n * n, 0.0), std::vector<double>(n, 0.0), mu};
  const auto cell = [&](std::size_t row, std::size_t column) -> double& { return problem.M[row * n + column]; };
  const auto response = [&](std::size_t row, std::size_t column) { return W[row * 2 * m + column]; };
  for (std::size_t i = 0; i < m; i++) {
    for (std::size_t j = 0; j < m; j++) {
      const double wnn = response(i, j), wnt = response(i, m + j), wtn = response(m + i, j),
                   wtt = response(m + i, m + j);
      cell(i, j) = wnn, cell(i, m + j) = wnt, cell(i, 2 * m + j) = -wnt;
      cell(m + i, j) = wtn, cell(m + i, m + j) = wtt, cell(m + i, 2 * m + j) = -wtt;
      cell(2 * m + i, j) = -wtn, cell(2 * m + i, m + j) = -wtt, cell(2 * m + i, 2 * m + j) = wtt;
    }
    cell(m + i, 3 * m + i) = 1.0;
    cell(2 * m + i, 3 * m + i) = 1.0;
    cell(3 * m + i, i) = mu[i], cell(3 * m + i, m + i) = -1.0, cell(3 * m + i, 2 * m + i) = -1.0;
    problem.q[i] = u0[i], problem.q[m + i] = u0[m + i], problem.q[2 * m + i] = -u0[m + i];
  }
  return problem;
}

}  // namespace cd
