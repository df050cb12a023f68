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

namespace {

TEST(FrictionlessLocalSolver, MatchesCoulombSolverAtZeroFriction)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> velocity(-1.0, 1.0), stiffness(0.5, 2.0), coupling(-0.4, 0.4);
  for (int k = 0; k < 10000; k++) {
    const double nn = stiffness(rng), tt = stiffness(rng);
    const cd::Delassus2 w{nn, coupling(rng) * std::sqrt(nn * tt), tt};    // SPD, coupled
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

constexpr double radius = 0.5;    // m, mean
constexpr double density = 1.0;   // kg/m^2
constexpr double gravity = 9.81;  // m/s^2
const cd::StepParameters step{1e-3, 0.5};

// A pile of disks on a hexagonal lattice of spacing 2 radius on the floor y = 0, radii a little
// below radius (small gaps), random velocities and spins: impacts, resting and separating
// contacts together.
struct Pile {
  cd::BodySet bodies;
  std::vector<cd::Contact> contacts;
};

Pile make_pile(double grain_mu, double floor_mu)
{
  constexpr int columns = 8, rows = 6;
  const cd::ContactLaw grain_law{grain_mu, 0.5}, floor_law{floor_mu, 0.5};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> shrink(0.0, 1e-3), speed(-0.05, 0.05), spin(-1.0, 1.0);

  Pile pile;
  std::vector<cd::Disk> disks;
  for (int row = 0; row < rows; row++)
    for (int column = 0; column < columns - row % 2; column++)
      disks.push_back({(2 * column + row % 2 + 1) * radius, (1.0 + row * std::sqrt(3.0)) * radius,
                       radius * (1.0 - shrink(rng))});
  const int count = static_cast<int>(disks.size());
  pile.bodies.reset(count + 1);
  for (int k = 0; k < count; k++) {
    const double mass = M_PI * disks[k].radius * disks[k].radius * density;
    pile.bodies.inertia[1 + k] = {1.0 / mass, 1.0 / (0.5 * mass * disks[k].radius * disks[k].radius)};
    pile.bodies.start_velocity[1 + k] = {speed(rng), speed(rng) - 0.05, spin(rng)};
    pile.bodies.velocity[1 + k] = pile.bodies.start_velocity[1 + k];
    pile.bodies.velocity[1 + k].vy -= gravity * step.dt;
  }

  auto add = [&](const cd::ContactGeometry& g, const cd::ContactLaw& law) {
    cd::Contact c = cd::contact_frame(g);
    if (!cd::is_candidate(c, pile.bodies, step, 0.01 * radius)) return;
    cd::prepare_mechanics(c, law, pile.bodies, step);
    pile.contacts.push_back(c);
  };
  for (int i = 0; i < count; i++) {
    if (disks[i].y < 1.5 * radius) add(cd::disk_world_geometry(1 + i, disks[i], 0.0, disks[i].y, 0.0, 1.0), floor_law);
    for (int j = i + 1; j < count; j++)
      if (std::hypot(disks[i].x - disks[j].x, disks[i].y - disks[j].y) < 2.5 * radius)
        add(cd::disk_disk_geometry(1 + i, disks[i], 1 + j, disks[j]), grain_law);
  }
  return pile;
}

cd::SolveReport solve(Pile& pile, bool frictionless_shortcut, double relaxation)
{
  cd::SolverSettings settings{1e-10, 10000, relaxation, cd::ConvergenceNorm::quadratic};
  settings.frictionless_shortcut = frictionless_shortcut;
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
