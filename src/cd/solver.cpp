// The solver seam's report and stopping settings (cd/solver.h).
#include "cd/solver.h"

#include <algorithm>

#include "cd/refusal.h"

namespace cd {

void SolveReport::add(const SolveReport& later)
{
  iterations += later.iterations;
  solves += later.solves;
  contact_updates += later.contact_updates;
  stalled_sweeps += later.stalled_sweeps;
  cold_restarts += later.cold_restarts;
  block_solves += later.block_solves;
  largest_block = std::max(largest_block, later.largest_block);
  kept_block_solves += later.kept_block_solves;
  newton_polishes += later.newton_polishes;
  newton_steps += later.newton_steps;
  residual = later.residual;
  converged = later.converged;
}

// Written so that NaN fails every test. A tolerance of 1 or more is met by any first sweep (the
// norm compares the sweep's change with the impulses' scale), one of 0 runs the cap's sweeps.
std::string check_stopping(const SolverSettings& settings)
{
  if (!(settings.tolerance >= 0.0 && settings.tolerance < 1.0))
    return refusal("tolerance", "in [0,1)", settings.tolerance);
  if (settings.max_iterations < 1) return refusal("max_iterations", ">= 1", settings.max_iterations);
  return {};
}

}  // namespace cd
