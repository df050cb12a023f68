// Ours as the peer comparison runs it (bench/peers/ours.h).
#include "ours.h"

namespace peers {

cd::SolverSettings deck_settings()
{
  cd::SolverSettings s;
  s.tolerance = 1e-3;
  s.max_iterations = 10000;
  s.gauss_seidel.acceleration = cd::Acceleration::conjugate;
  s.gauss_seidel.full_sweep_every = 8;
  s.gauss_seidel.stall_window = 100;
  return s;
}

void solve_down_the_ladder(std::vector<cd::Contact>& contacts, std::vector<cd::BodyVelocity>& velocity,
                           cd::SweepObserver& observer, bool newton_polish, Ladder& ladder)
{
  cd::SolverSettings settings = deck_settings();
  settings.gauss_seidel.newton_polish = newton_polish;
  for (;; settings.tolerance /= 10.0) {
    cd::GaussSeidel solver(settings);
    solver.observe(&observer);
    ladder.solves++;
    ladder.finished.add(solver.solve(contacts, velocity));
    if (settings.tolerance < 1e-15) break;
  }
}

}  // namespace peers
