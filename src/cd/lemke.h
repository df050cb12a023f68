// Lemke's complementary pivoting for a dense linear complementarity problem: find z with
// w = M z + q, w >= 0, z >= 0, w . z = 0. The ratio test is lexicographic, so the pivoting
// terminates on degenerate problems (granular blocks are full of them). It ends either at a
// solution or on a ray, where the method proves nothing (for the frictional contact problems it
// serves, cd/block_solve.h, that means the block has no solution it can reach).
#pragma once

#include <vector>

namespace cd {

struct LemkeResult {
  bool solved = false;
  int pivots = 0;
};

// M is n x n, row-major; z (resized to n) receives the solution. Stops unsolved after
// max_pivots pivots. The work is O(n^2) per pivot in a tableau of n x (n + 2) doubles (the nonbasic
// variables' columns), kept from solve to solve by the calling thread.
LemkeResult solve_lcp_lemke(const std::vector<double>& M, const std::vector<double>& q, std::vector<double>& z,
                            int max_pivots);

}  // namespace cd
