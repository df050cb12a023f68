// Ours as the peer comparison runs it (bench/peers/ours.h).
#include "ours.h"

#include <algorithm>
#include <stdexcept>

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

const std::vector<std::string>& ours_names()
{
  static const std::vector<std::string> names{"ours", "ours_newton", "ours_over_relaxed"};
  return names;
}

bool is_ours(const std::string& name)
{
  return std::count(ours_names().begin(), ours_names().end(), name) > 0;
}

cd::SolverSettings ours_settings(const std::string& name)
{
  cd::SolverSettings s = deck_settings();
  if (name == "ours_newton") s.gauss_seidel.newton_polish = true;
  else if (name == "ours_over_relaxed") s.gauss_seidel.over_relaxation = 1.8;
  else if (name != "ours") throw std::invalid_argument("not one of ours: '" + name + "'");
  return s;
}

void solve_down_the_ladder(std::vector<cd::Contact>& contacts, std::vector<cd::BodyVelocity>& velocity,
                           cd::SweepObserver& observer, const cd::SolverSettings& ladder_top, Ladder& ladder)
{
  cd::SolverSettings settings = ladder_top;
  for (;; settings.tolerance /= 10.0) {
    cd::GaussSeidel solver(settings);
    solver.observe(&observer);
    ladder.solves++;
    ladder.finished.add(solver.solve(contacts, velocity));
    if (settings.tolerance < 1e-15) break;
  }
}

}  // namespace peers
