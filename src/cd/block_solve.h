// An exact solve of a block of contacts, every other impulse frozen: the tool Gauss–Seidel's
// stall rescue ends with (cd/gauss_seidel.h). At mu 2 the steps that no sweep settles carry
// 90 % of their residual in 3 to 25 contacts, in clusters of a few grains (doc/stalls.md); a
// block around those, solved exactly, puts them where no sweep could.
//
// A 2D Coulomb–Signorini problem on a block is a linear complementarity problem, the friction
// cone being a pair of half-planes. Per contact: the normal impulse p_n, the tangential impulse's
// two sides p_t = p_+ - p_-, and the sliding speed s:
//   u_n >= 0 ⊥ p_n >= 0,   s + u_t >= 0 ⊥ p_+ >= 0,   s - u_t >= 0 ⊥ p_- >= 0,
//   mu p_n - p_+ - p_- >= 0 ⊥ s >= 0,
// with u the law velocity (cd::law_velocity), affine in the block's impulses. The contacts'
// states from the sweeps' iterate mostly fix its answer (cd/friction_states.h); Lemke's method
// (cd/lemke.h) solves what they do not.
#pragma once

#include <cstddef>
#include <vector>

#include "cd/block_problem.h"
#include "cd/contact.h"

namespace cd {

struct BlockSolve {
  int clusters = 0;
  int unsolved = 0;  // clusters left on a ray, at the pivot cap or refused (their impulses kept)
  int pivots = 0;
};

// A block's problem (cd/block_problem.h), the law acting on u + rho (p - p_k) (solve_block), its m
// contacts in block order.
BlockProblem block_problem(const std::vector<Contact>& contacts, const std::vector<BodyVelocity>& velocity,
                           const std::vector<int>& block);

// Solves the block's contacts (indices into `contacts`) with every other impulse frozen, and
// applies the change of their impulses to `velocity`. The law acts on u + rho (p - p_k), with p_k
// the impulses before and rho = 1e-4 W_ii per contact: of a hyperstatic block's solutions, the one
// nearest p_k, exact to about 1e-4 of the change (repeated, to round-off). Each cluster of the block (contacts
// linked through shared mobile bodies) is a problem of its own; one that Lemke does not solve,
// or whose answer would still carry a runaway self-stress (impulses 100 times the cluster's
// scale, see block_solve.cpp), keeps its impulses.
BlockSolve solve_block(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                       const std::vector<int>& block);

// The contacts that carry `share` of the squared natural-map residual of the iterate (the
// Coulomb law's violation, cd::natural_map_residual_squared, in W_nn-scaled impulse units),
// largest first, at most `max_count`.
std::vector<int> residual_carriers(const std::vector<Contact>& contacts, const std::vector<BodyVelocity>& velocity,
                                   double share, int max_count);

// The most contacts a rescue's block may hold in a solve of `contact_count` contacts after
// `sweeps` sweeps (the stall window and those since the first stall): Lemke's work on a block of
// m contacts (about 50 ns m^3 on the chute's trapped steps, the worst case of the exact solve)
// stays within that of the sweeps (about 50 ns per contact and sweep), (sweeps contact_count)^(1/3),
// at least `seeds` and at most 200 (the dense tableau's memory). At the first stall a chute of
// 4 800 contacts gets 78, a rank's 190 contacts of a 2-rank cell 26 (doc/stalls.md).
int block_budget(int sweeps, std::size_t contact_count, int seeds);

// The block around `seeds` (indices into `contacts`): the seeds and every contact reached from
// them through `hops` shared bodies (the world, body 0, links nothing), at most `max_size`
// contacts, nearest first. Sorted by index.
std::vector<int> block_around(const std::vector<Contact>& contacts, int body_count, const std::vector<int>& seeds,
                              int hops, int max_size);

}  // namespace cd
