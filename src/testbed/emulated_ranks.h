// The sweep of a run decomposed over ranks, reproduced on one rank, on top of the solver core:
// a study instrument (how much the block coupling of a decomposed sweep costs), not a solver
// option. The contacts form consecutive blocks, one per rank (block_ends: the end of each,
// increasing, the last contacts.size()); each block sweeps in order from the velocities at the
// start of the sweep and the blocks' velocity changes are summed, as ranks sum the changes of
// their ghosts into the owners after a sweep. A body touched by two blocks is updated by both.
#pragma once

#include <cstddef>
#include <vector>

#include "cd/gauss_seidel.h"

namespace testbed {

cd::SweepChange sweep_in_blocks(std::vector<cd::Contact>& contacts, const std::vector<std::size_t>& block_ends,
                                std::vector<cd::BodyVelocity>& velocity, const cd::SolverSettings& settings);

// cd::solve_gauss_seidel with every sweep made by sweep_in_blocks.
cd::SolveReport solve_in_blocks(std::vector<cd::Contact>& contacts, const std::vector<std::size_t>& block_ends,
                                std::vector<cd::BodyVelocity>& velocity, const cd::SolverSettings& settings);

}  // namespace testbed
