// The convergence norms are dimensionless and measure what they claim.
#include <gtest/gtest.h>

#include <cmath>

#include "cd/convergence.h"
#include "cd/gauss_seidel.h"

namespace {

TEST(ConvergenceNorm, QuadraticAndMaximumOnKnownSums)
{
  cd::SweepChange change;
  change.add({3.0, 4.0}, {6.0, 8.0});   // |dv| = 5, |v| = 10
  change.add({0.0, 0.0}, {0.0, 10.0});  // |dv| = 0, |v| = 10
  EXPECT_DOUBLE_EQ(change.residual(cd::ConvergenceNorm::quadratic), std::sqrt(25.0 / 200.0));
  EXPECT_DOUBLE_EQ(change.residual(cd::ConvergenceNorm::maximum), 5.0 / 10.0);
}

TEST(ConvergenceNorm, EdgeCases)
{
  cd::SweepChange none;
  EXPECT_EQ(none.residual(cd::ConvergenceNorm::quadratic), 0.0);
  cd::SweepChange released;
  released.add({1.0, 0.0}, {0.0, 0.0});
  EXPECT_TRUE(std::isinf(released.residual(cd::ConvergenceNorm::maximum)));
}

// The same column problem in SI and in scaled units needs the same iterations and residual.
TEST(ConvergenceNorm, ScaleFreeAcrossUnits)
{
  auto run = [](double length, double mass_unit, double time) {
    cd::BodySet bodies;
    const int n = 8;
    bodies.reset(n + 1);
    std::vector<cd::Contact> contacts;
    const double r = 0.5 * length, m = mass_unit, g = 9.81 * length / (time * time), dt = 1e-3 * time;
    for (int k = 1; k <= n; k++) {
      bodies.inertia[k] = {1.0 / m, 1.0 / (0.5 * m * r * r)};
      bodies.velocity[k] = {0.0, -g * dt, 0.0};
      const cd::ContactGeometry g_k =
          k == 1 ? cd::disk_world_geometry(1, cd::Disk{0, r, r}, 0.0, r, 0.0, 1.0)
                 : cd::disk_disk_geometry(k, cd::Disk{0, (2 * k - 1) * r, r}, k - 1, cd::Disk{0, (2 * k - 3) * r, r});
      contacts.push_back(cd::prepared_contact(g_k, {0.5, 0.0}, bodies, {dt, 0.5}));
    }
    return cd::solve_gauss_seidel(contacts, bodies.velocity, {1e-6, 10000, cd::ConvergenceNorm::quadratic});
  };
  const cd::SolveReport si = run(5e-4, 2e-4, 7e-3);
  const cd::SolveReport scaled = run(1.0, 1.0, 1.0);
  EXPECT_TRUE(si.converged);
  EXPECT_EQ(si.iterations, scaled.iterations);
  EXPECT_NEAR(si.residual, scaled.residual, 1e-9);
}

}  // namespace
