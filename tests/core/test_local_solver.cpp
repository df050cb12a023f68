// The exact 2D Coulomb local solver: each branch against its closed form, and the natural map.
#include <gtest/gtest.h>

#include <random>

#include "cd/coulomb_local.h"

namespace {

const cd::Delassus2 diagonal{2.0, 0.0, 6.0};

TEST(LocalSolver, SeparatingContactCarriesNoImpulse)
{
  const auto s = cd::solve_coulomb_local(diagonal, {0.3, -5.0}, 0.5);
  EXPECT_EQ(s.status, cd::ContactStatus::no_contact);
  EXPECT_EQ(s.impulse.n, 0.0);
  EXPECT_EQ(s.impulse.t, 0.0);
}

TEST(LocalSolver, StickCancelsTheRelativeVelocity)
{
  const auto s = cd::solve_coulomb_local(diagonal, {-1.0, 0.6}, 0.5);
  EXPECT_EQ(s.status, cd::ContactStatus::stick);
  EXPECT_DOUBLE_EQ(s.impulse.n, 0.5);   // 1.0 / 2
  EXPECT_DOUBLE_EQ(s.impulse.t, -0.1);  // -0.6 / 6
}

TEST(LocalSolver, SlipSaturatesFrictionAgainstTheSlidingDirection)
{
  const auto forward = cd::solve_coulomb_local(diagonal, {-1.0, 6.0}, 0.5);
  EXPECT_EQ(forward.status, cd::ContactStatus::slip_positive);
  EXPECT_DOUBLE_EQ(forward.impulse.n, 0.5);
  EXPECT_DOUBLE_EQ(forward.impulse.t, -0.25);
  const auto backward = cd::solve_coulomb_local(diagonal, {-1.0, -6.0}, 0.5);
  EXPECT_EQ(backward.status, cd::ContactStatus::slip_negative);
  EXPECT_DOUBLE_EQ(backward.impulse.t, 0.25);
}

TEST(LocalSolver, FrictionlessContactHasNoTangentialImpulse)
{
  const auto s = cd::solve_coulomb_local(diagonal, {-1.0, 3.0}, 0.0);
  EXPECT_DOUBLE_EQ(s.impulse.n, 0.5);
  EXPECT_EQ(s.impulse.t, 0.0);
}

// The sweep's closed form for disks (W_nt = 0) gives the general solver's impulse on every
// branch: separating, sticking, slipping either way, frictionless and near-infinite friction.
TEST(LocalSolver, DiskClosedFormMatchesTheGeneralSolver)
{
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (double mu : {0.0, 0.05, 0.5, 2.0, 1e6}) {
    for (int trial = 0; trial < 2000; trial++) {
      const cd::DiskDelassus w = cd::DiskDelassus::of(0.5 + std::abs(unit(rng)), 0.5 + std::abs(unit(rng)));
      const cd::Local2 u_free{unit(rng), unit(rng)};
      const cd::Local2 general = cd::solve_coulomb_local(w.full(), u_free, mu).impulse;
      const cd::Local2 disk = cd::solve_coulomb_disk({-w.inverse_nn * u_free.n, -w.inverse_tt * u_free.t}, mu);
      // Both are O(1) and computed with a few roundings each.
      EXPECT_NEAR(disk.n, general.n, 1e-15) << "mu " << mu << " trial " << trial;
      EXPECT_NEAR(disk.t, general.t, 1e-15 * (1.0 + mu)) << "mu " << mu << " trial " << trial;
    }
  }
}

TEST(LocalSolver, CoupledDelassusSolutionsSatisfyCoulombLaw)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (double mu : {0.0, 0.05, 0.5, 2.0, 1e6}) {
    for (int trial = 0; trial < 2000; trial++) {
      const double a = 0.5 + std::abs(unit(rng)), c = 0.5 + std::abs(unit(rng));
      const cd::Delassus2 w{a, 0.3 * std::sqrt(a * c) * unit(rng), c};  // SPD, weakly coupled
      const cd::Local2 u_free{unit(rng), unit(rng)};
      const cd::Local2 p = cd::solve_coulomb_local(w, u_free, mu).impulse;
      const cd::Local2 wp = w.times(p);
      const cd::Local2 u{u_free.n + wp.n, u_free.t + wp.t};
      // Exact up to rounding: u is O(1) with error ~1e-16, which De Saxce's term mu |u_t|
      // amplifies by mu.
      const double rounding = 1e-13 * (1.0 + mu);
      EXPECT_LT(cd::natural_map_residual_squared(p, u, mu), rounding * rounding) << "mu " << mu << " trial " << trial;
    }
  }
}

TEST(NaturalMap, DetectsViolations)
{
  // Penetrating velocity with no impulse, friction outside the cone, stick with slip.
  EXPECT_GT(cd::natural_map_residual_squared({0.0, 0.0}, {-1.0, 0.0}, 0.5), 0.5);
  EXPECT_GT(cd::natural_map_residual_squared({1.0, 0.9}, {0.0, 0.0}, 0.5), 0.1);
  EXPECT_GT(cd::natural_map_residual_squared({1.0, 0.1}, {0.0, 0.4}, 0.5), 0.01);
  EXPECT_EQ(cd::natural_map_residual_squared({1.0, -0.5}, {0.0, 0.4}, 0.5), 0.0);
}

}  // namespace
