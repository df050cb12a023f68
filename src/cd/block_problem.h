// A block's 2D Coulomb–Signorini problem as a linear complementarity problem (cd/block_solve.h
// says why): find z >= 0 with w = M z + q >= 0, w . z = 0, over the unknowns (p_n, p_+, p_-, s)
// of its m contacts, p_t = p_+ - p_- and s the sliding speed:
//   rows 0..m:    u_n = q_n + W_nn p_n + W_nt p_t                 ⊥ p_n
//   rows m..2m:   s + u_t                                         ⊥ p_+
//   rows 2m..3m:  s - u_t                                         ⊥ p_-
//   rows 3m..4m:  mu p_n - p_+ - p_-                              ⊥ s
// Its exact solvers: cd/friction_states.h, cd/lemke.h.
#pragma once

#include <vector>

namespace cd {

struct BlockProblem {
  std::vector<double> M;   // 4m x 4m, row-major
  std::vector<double> q;   // 4m: (u_n, u_t, -u_t, 0) at zero block impulses
  std::vector<double> mu;  // m: the contacts' frictions
};

// The problem of a block whose law velocities respond as u = u0 + W p: W 2m x 2m row-major, rows
// (u_n of each contact, then u_t of each), columns (p_n of each, then p_t of each); u0 2m.
BlockProblem block_lcp(const std::vector<double>& W, const std::vector<double>& u0, const std::vector<double>& mu);

}  // namespace cd
