// A block's 2D Coulomb–Signorini problem (cd/block_solve.h says why it is solved): its m contacts'
// law velocities respond to their impulses as u = u0 + W p, each contact on its Coulomb law with
// friction mu. Its exact solvers read it as it is (the contacts' states, cd/friction_states.h) or
// as a linear complementarity problem (Lemke's method, cd/lemke.h): to_lcp gives that problem,
// impulses_from_lcp turns its solution back into impulses.
#pragma once

#include <cstddef>
#include <vector>

#include "cd/coulomb_local.h"

namespace cd {

struct BlockProblem {
  // 2m x 2m, row-major: rows (u_n of each contact, then u_t of each), columns (p_n of each, then
  // p_t of each).
  std::vector<double> W;
  std::vector<double> u0;  // 2m: the law velocities at zero block impulses, (u_n..., u_t...)
  std::vector<double> mu;  // m: the contacts' frictions

  std::size_t size() const { return mu.size(); }
  // W's 2x2 block of contacts i and j: d u_i{n,t} / d p_j{n,t}.
  double nn(std::size_t i, std::size_t j) const { return W[i * 2 * size() + j]; }
  double nt(std::size_t i, std::size_t j) const { return W[i * 2 * size() + size() + j]; }
  double tn(std::size_t i, std::size_t j) const { return W[(size() + i) * 2 * size() + j]; }
  double tt(std::size_t i, std::size_t j) const { return W[(size() + i) * 2 * size() + size() + j]; }
  // Contact i's law velocity at the block's impulses p.
  Local2 velocity(std::size_t i, const std::vector<Local2>& p) const;
  // The largest |u_n| or |u_t| at zero block impulses.
  double velocity_scale() const;
};

// The block's problem as a linear complementarity problem: find z >= 0 with w = M z + q >= 0,
// w . z = 0, over the unknowns (p_n, p_+, p_-, s) of its m contacts, p_t = p_+ - p_- and s the
// sliding speed:
//   rows 0..m:    u_n = q_n + W_nn p_n + W_nt p_t                 ⊥ p_n
//   rows m..2m:   s + u_t                                         ⊥ p_+
//   rows 2m..3m:  s - u_t                                         ⊥ p_-
//   rows 3m..4m:  mu p_n - p_+ - p_-                              ⊥ s
struct BlockLcp {
  std::vector<double> M;  // 4m x 4m, row-major
  std::vector<double> q;  // 4m: (u_n, u_t, -u_t, 0) at zero block impulses
};
BlockLcp to_lcp(const BlockProblem& problem);

// The impulses of a solution z of to_lcp's problem of m contacts: p_n = z_n, p_t = p_+ - p_-
// (each side's round-off below zero dropped).
std::vector<Local2> impulses_from_lcp(const std::vector<double>& z, std::size_t m);

}  // namespace cd
