// The frictionless shortcut (mu = 0 contacts solve only p_n and touch no spin) gives what the
// Coulomb local solver gives for mu = 0: the same local solutions, and on a small pile the same
// impulses, velocities and sweep counts to round-off, with spins untouched by the contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "cd/gauss_seidel.h"
#include "pile.h"

namespace {

TEST(FrictionlessLocalSolver, MatchesCoulombSolverAtZeroFriction)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> velocity(-1.0, 1.0), stiffness(0.5, 2.0), coupling(-0.4, 0.4);
  for (int k = 0; k < 10000; k++) {
    const double nn = stiffness(rng), tt = stiffness(rng);
    const cd::Delassus2 w{nn, coupling(rng) * std::sqrt(nn * tt), tt};  // SPD, coupled
    const cd::Local2 u_free{velocity(rng), velocity(rng)};
    const cd::LocalSolution coulomb = cd::solve_coulomb_local(w, u_free, 0.0);
    const double p_n = cd::solve_frictionless_local(w, u_free.n);
    // Both take p_n = -u_free.n / W_nn; only an exactly zero u_t (stick branch) may differ by
    // an ulp, hence the relative 1e-15.
    EXPECT_NEAR(p_n, coulomb.impulse.n, 1e-15 * std::abs(p_n)) << k;
    EXPECT_EQ(coulomb.impulse.t, 0.0) << k;
    EXPECT_GE(p_n, 0.0);
    // Signorini: u_n = W_nn p_n + u_free.n is zero under load and non-negative without.
    const double u_n = nn * p_n + u_free.n;
    if (p_n > 0.0) EXPECT_NEAR(u_n, 0.0, 1e-15);
    else EXPECT_GE(u_n, 0.0);
  }
}

cd::SolveReport solve(Pile& pile, bool frictionless_shortcut, double relaxation)
{
  cd::SolverSettings settings{1e-10, 10000, cd::ConvergenceNorm::quadratic};
  settings.gauss_seidel.relaxation = relaxation;
  settings.gauss_seidel.frictionless_shortcut = frictionless_shortcut;
  cd::apply_impulses(pile.contacts, pile.bodies.velocity);
  return cd::solve_gauss_seidel(pile.contacts, pile.bodies.velocity, settings);
}

double largest_normal_impulse(const Pile& pile)
{
  double largest = 0.0;
  for (const cd::Contact& c : pile.contacts) largest = std::max(largest, c.impulse.n);
  return largest;
}

// Both piles solved from the same state: impulses and velocities agree to round-off. The two
// paths compute the same numbers except when u_t is exactly zero, where the Coulomb solver's
// stick branch rounds differently by an ulp; Gauss–Seidel does not amplify that, so 1e-12 of
// the largest impulse (and of the velocity it makes) bounds any difference with a wide margin.
void expect_same_solution(const Pile& shortcut, const Pile& coulomb)
{
  ASSERT_EQ(shortcut.contacts.size(), coulomb.contacts.size());
  const double impulse_scale = largest_normal_impulse(coulomb);
  ASSERT_GT(impulse_scale, 0.0);
  for (std::size_t k = 0; k < coulomb.contacts.size(); k++) {
    EXPECT_NEAR(shortcut.contacts[k].impulse.n, coulomb.contacts[k].impulse.n, 1e-12 * impulse_scale) << k;
    EXPECT_NEAR(shortcut.contacts[k].impulse.t, coulomb.contacts[k].impulse.t, 1e-12 * impulse_scale) << k;
  }
  const double velocity_scale = impulse_scale * shortcut.bodies.inertia[1].inv_mass;
  for (std::size_t b = 1; b < coulomb.bodies.velocity.size(); b++) {
    const cd::BodyVelocity& s = shortcut.bodies.velocity[b];
    const cd::BodyVelocity& c = coulomb.bodies.velocity[b];
    EXPECT_NEAR(s.vx, c.vx, 1e-12 * velocity_scale) << b;
    EXPECT_NEAR(s.vy, c.vy, 1e-12 * velocity_scale) << b;
    EXPECT_NEAR(s.spin, c.spin, 1e-12 * velocity_scale / radius) << b;
  }
}

// (relaxation, floor mu): all frictionless, and frictionless grains on a rough floor.
class FrictionlessShortcut : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(FrictionlessShortcut, SameSolveAsCoulombSolver)
{
  const auto [relaxation, floor_mu] = GetParam();
  Pile shortcut = make_pile(0.0, floor_mu), coulomb = make_pile(0.0, floor_mu);
  ASSERT_GT(shortcut.contacts.size(), 100u);
  const cd::SolveReport with = solve(shortcut, true, relaxation);
  const cd::SolveReport without = solve(coulomb, false, relaxation);
  EXPECT_TRUE(with.converged);
  EXPECT_EQ(with.iterations, without.iterations);
  expect_same_solution(shortcut, coulomb);

  // Frictionless contacts carry no tangential impulse; with a frictionless floor too, every
  // grain keeps the spin it had (no torque acts here): exactly, not to round-off.
  for (const cd::Contact& c : shortcut.contacts)
    if (c.mu == 0.0) EXPECT_EQ(c.impulse.t, 0.0);
  if (floor_mu == 0.0)
    for (std::size_t b = 1; b < shortcut.bodies.velocity.size(); b++)
      EXPECT_EQ(shortcut.bodies.velocity[b].spin, shortcut.bodies.start_velocity[b].spin) << b;
}

INSTANTIATE_TEST_SUITE_P(RelaxationAndFloor, FrictionlessShortcut,
                         ::testing::Combine(::testing::Values(1.0, 0.8), ::testing::Values(0.0, 0.5)));

// A tangential impulse carried into a frictionless contact (a run restarted with mu = 0) is
// dropped by the warm start: the same solution as applying it and letting the Coulomb solver
// remove it in the first sweep.
TEST(FrictionlessShortcut, WarmStartDropsCarriedTangentialImpulse)
{
  Pile shortcut = make_pile(0.0, 0.5), coulomb = make_pile(0.0, 0.5);
  for (std::size_t k = 0; k < coulomb.contacts.size(); k++) {
    const cd::Local2 carried{1e-3 * (1.0 + 0.1 * static_cast<double>(k % 7)), 2e-4 * ((k % 3) - 1.0)};
    cd::warm_start(shortcut.contacts[k], carried);
    coulomb.contacts[k].impulse = carried;
    const double expected_t = shortcut.contacts[k].mu == 0.0 ? 0.0 : carried.t;
    EXPECT_EQ(shortcut.contacts[k].impulse.n, carried.n);
    EXPECT_EQ(shortcut.contacts[k].impulse.t, expected_t);
  }
  solve(shortcut, true, 1.0);
  solve(coulomb, false, 1.0);
  expect_same_solution(shortcut, coulomb);
}

}  // namespace
