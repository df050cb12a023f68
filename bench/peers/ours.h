// Ours as the peer comparison runs it (doc/peers.md): Gauss–Seidel at the deck's settings
// (inputs/in.chute), gone on with its tolerance ten times lower each time its own norm ends a
// solve, down to 1e-16. Shared by peer_bench and peer_limits.
#pragma once

#include <string>
#include <vector>

#include "cd/gauss_seidel.h"

namespace peers {

// The fix's defaults, then inputs/in.chute's solver variables.
cd::SolverSettings deck_settings();

// Ours' names in the comparison: ours (deck_settings), ours_newton (with the Newton polish,
// cd/newton_polish.h), ours_over_relaxed (over_relaxation 1.8, cd/gauss_seidel_settings.h).
const std::vector<std::string>& ours_names();
bool is_ours(const std::string& name);
// The settings of one of ours_names(); throws std::invalid_argument for another name.
cd::SolverSettings ours_settings(const std::string& name);

// The solves so far: an observer adds the finished ones to the report of the solve under way.
struct Ladder {
  int solves = 0;
  cd::SolveReport finished;  // iterations: the sweeps before the solve under way
  cd::SolveReport so_far(const cd::SolveReport& current) const
  {
    cd::SolveReport total = finished;
    total.add(current);
    return total;
  }
};

// Solves from the contacts' impulses (already applied to `velocity`) with `settings` down the
// ladder of tolerances, from theirs; `observer` sees every full sweep and may end the run by throwing.
void solve_down_the_ladder(std::vector<cd::Contact>& contacts, std::vector<cd::BodyVelocity>& velocity,
                           cd::SweepObserver& observer, const cd::SolverSettings& settings, Ladder& ladder);

}  // namespace peers
