#include "testbed/emulated_ranks.h"

namespace testbed {

cd::SweepChange sweep_in_blocks(std::vector<cd::Contact>& contacts, const std::vector<std::size_t>& block_ends,
                                std::vector<cd::BodyVelocity>& velocity, const cd::SolverSettings& settings)
{
  const std::vector<cd::BodyVelocity> start = velocity;
  std::vector<cd::BodyVelocity> block_velocity;
  cd::SweepChange change;
  std::size_t block_start = 0;
  for (const std::size_t block_end : block_ends) {
    block_velocity = start;
    change.merge(
        cd::sweep(contacts.data() + block_start, contacts.data() + block_end, block_velocity.data(), settings));
    for (std::size_t b = 0; b < velocity.size(); b++) {
      velocity[b].vx += block_velocity[b].vx - start[b].vx;
      velocity[b].vy += block_velocity[b].vy - start[b].vy;
      velocity[b].spin += block_velocity[b].spin - start[b].spin;
    }
    block_start = block_end;
  }
  return change;
}

cd::SolveReport solve_in_blocks(std::vector<cd::Contact>& contacts, const std::vector<std::size_t>& block_ends,
                                std::vector<cd::BodyVelocity>& velocity, const cd::SolverSettings& settings)
{
  cd::SolveReport report;
  while (report.iterations < settings.max_iterations) {
    const cd::SweepChange change = sweep_in_blocks(contacts, block_ends, velocity, settings);
    ++report.iterations;
    report.residual = change.residual(settings.norm);
    if (report.residual <= settings.tolerance) return report;
  }
  report.converged = false;
  return report;
}

}  // namespace testbed
