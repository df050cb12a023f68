// Binary impacts of rigid disks against the analytic impact laws (Newton restitution, Coulomb
// friction): post-impact velocities for e in {0, 0.5, 1} and mu in {0, 0.5, 1e6}.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "cd/gauss_seidel.h"

namespace {

constexpr double radius = 0.5;
constexpr double mass = 2.0;
constexpr double inertia = 0.5 * mass * radius * radius;

struct Impact {
  cd::BodySet bodies;
  cd::Contact contact;
  double gap = 0.0;  // m
};

// Disk a at the origin moving with (vx, vy) and spin; disk b at rest, touching a on its +x side.
Impact make_impact(double vx, double vy, double spin, double mu, double e)
{
  Impact impact;
  impact.bodies.reset(3);
  for (int body : {1, 2}) impact.bodies.inertia[body] = {1.0 / mass, 1.0 / inertia};
  impact.bodies.start_velocity[1] = {vx, vy, spin};
  impact.bodies.velocity = impact.bodies.start_velocity;
  const cd::ContactGeometry g =
      cd::disk_disk_geometry(1, cd::Disk{0.0, 0.0, radius}, 2, cd::Disk{2.0 * radius, 0.0, radius});
  impact.contact = cd::contact_frame(g);
  impact.gap = g.gap;
  EXPECT_TRUE(cd::is_candidate(impact.contact, g.gap, impact.bodies, {1e-3, 0.5}, 0.0));
  cd::prepare_mechanics(impact.contact, g.gap, {mu, e}, impact.bodies, {1e-3, 0.5});
  return impact;
}

cd::SolveReport solve(Impact& impact)
{
  std::vector<cd::Contact> contacts{impact.contact};
  const cd::SolveReport report =
      cd::solve_gauss_seidel(contacts, impact.bodies.velocity, {1e-12, 100, cd::ConvergenceNorm::quadratic});
  impact.contact = contacts[0];
  return report;
}

class BinaryImpact : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(BinaryImpact, HeadOnFollowsNewtonRestitution)
{
  const auto [e, mu] = GetParam();
  const double v = 1.3;
  Impact impact = make_impact(v, 0.0, 0.0, mu, e);
  EXPECT_TRUE(solve(impact).converged);
  const auto& after = impact.bodies.velocity;
  // Equal masses: v_a' = v (1 - e)/2, v_b' = v (1 + e)/2, no tangential motion.
  EXPECT_NEAR(after[1].vx, v * (1.0 - e) / 2.0, 1e-12);
  EXPECT_NEAR(after[2].vx, v * (1.0 + e) / 2.0, 1e-12);
  EXPECT_NEAR(after[1].vy, 0.0, 1e-12);
  EXPECT_NEAR(after[1].spin, 0.0, 1e-12);
  EXPECT_NEAR(after[2].spin, 0.0, 1e-12);
}

TEST_P(BinaryImpact, ObliqueImpactMatchesCoulombImpactLaw)
{
  const auto [e, mu] = GetParam();
  const double v = 2.0, angle = 0.6;  // incidence measured from the line of centres
  const double vn = v * std::cos(angle), vt = v * std::sin(angle);
  Impact impact = make_impact(vn, vt, 0.0, mu, e);
  EXPECT_TRUE(solve(impact).converged);
  const auto& after = impact.bodies.velocity;

  // Normal: p_n = (1 + e) m* vn with reduced mass m* = m/2.
  const double p_n = (1.0 + e) * vn * mass / 2.0;
  // Tangential: sticking needs the impulse that stops the contact-point slip, vt / W_tt with
  // W_tt = 2/m + 2 r^2/I = 6/m; otherwise the impulse saturates at mu p_n.
  const double p_stick = vt * mass / 6.0;
  const double p_t = std::min(p_stick, mu * p_n);  // magnitude, opposing the slip of a
  EXPECT_NEAR(after[1].vx, vn - p_n / mass, 1e-10);
  EXPECT_NEAR(after[2].vx, p_n / mass, 1e-10);
  EXPECT_NEAR(after[1].vy, vt - p_t / mass, 1e-10);
  EXPECT_NEAR(after[2].vy, p_t / mass, 1e-10);
  // The friction impulse acts at the contact points (+r x on a, -r x on b): both disks spin
  // clockwise when a slides upward past b.
  EXPECT_NEAR(after[1].spin, -radius * p_t / inertia, 1e-10);
  EXPECT_NEAR(after[2].spin, -radius * p_t / inertia, 1e-10);

  // Independent invariants: linear momentum, and each disk's angular momentum about the
  // contact point (the impulse has no moment there).
  EXPECT_NEAR(mass * (after[1].vy + after[2].vy), mass * vt, 1e-10);
  const double contact_moment_a = inertia * after[1].spin - mass * radius * after[1].vy;
  EXPECT_NEAR(contact_moment_a, -mass * radius * vt, 1e-10);
  if (p_stick <= mu * p_n) {
    const cd::Local2 u = cd::relative_velocity(impact.contact, after[1], after[2]);
    EXPECT_NEAR(u.t, 0.0, 1e-10);
  }
}

INSTANTIATE_TEST_SUITE_P(RestitutionAndFriction, BinaryImpact,
                         ::testing::Combine(::testing::Values(0.0, 0.5, 1.0), ::testing::Values(0.0, 0.5, 1e6)));

TEST(BinaryImpact, ElasticFrictionlessImpactConservesEnergy)
{
  Impact impact = make_impact(1.0, 0.7, 3.0, 0.0, 1.0);
  solve(impact);
  const auto energy = [](const cd::BodyVelocity& v) {
    return 0.5 * mass * (v.vx * v.vx + v.vy * v.vy) + 0.5 * inertia * v.spin * v.spin;
  };
  const double before = energy(impact.bodies.start_velocity[1]);
  const double after = energy(impact.bodies.velocity[1]) + energy(impact.bodies.velocity[2]);
  EXPECT_NEAR(after, before, 1e-12 * before);
}

// Two unit disks, b at rest, a with velocity (vx, 0) and free velocity (vx_free, 0), at `gap`.
struct PairNearContact {
  cd::BodySet bodies;
  cd::Contact contact;
  double gap = 0.0;  // m
};

PairNearContact pair_near_contact(double gap, double vx, double vx_free)
{
  PairNearContact pair;
  pair.bodies.reset(3);
  pair.bodies.inertia[1] = pair.bodies.inertia[2] = {1.0, 2.0};
  pair.bodies.start_velocity[1] = {vx, 0.0, 0.0};
  pair.bodies.velocity[1] = {vx_free, 0.0, 0.0};
  const cd::ContactGeometry g = cd::disk_disk_geometry(1, cd::Disk{0.0, 0.0, 0.5}, 2, cd::Disk{1.0 + gap, 0.0, 0.5});
  pair.contact = cd::contact_frame(g);
  pair.gap = g.gap;
  return pair;
}

TEST(Candidates, OnlyPairsThatCanMeetWithinTheStepAreSolved)
{
  const cd::StepParameters step{1e-3, 0.5};
  const PairNearContact opening = pair_near_contact(1e-3, -1.0, -1.0);
  EXPECT_FALSE(cd::is_candidate(opening.contact, opening.gap, opening.bodies, step, 1e-4));
  const PairNearContact closing = pair_near_contact(1e-3, 2.0, 2.0);  // closes 1e-3 in the step
  EXPECT_TRUE(cd::is_candidate(closing.contact, closing.gap, closing.bodies, step, 0.0));
  const PairNearContact near = pair_near_contact(5e-5, 0.0, 0.0);
  EXPECT_TRUE(cd::is_candidate(near.contact, near.gap, near.bodies, step, 1e-4));
  EXPECT_FALSE(cd::is_candidate(near.contact, near.gap, near.bodies, step, 1e-5));
}

TEST(Candidates, FastApproachFromAGapRebounds)
{
  // Meets within the step at its pre-step velocity: an impact, rebounding with e from a gap.
  const cd::StepParameters step{1e-3, 0.5};
  PairNearContact pair = pair_near_contact(2e-4, 1.0, 1.0);
  cd::prepare_mechanics(pair.contact, pair.gap, {0.0, 0.5}, pair.bodies, step);
  std::vector<cd::Contact> contacts{pair.contact};
  cd::solve_gauss_seidel(contacts, pair.bodies.velocity, {});
  EXPECT_NEAR(pair.bodies.velocity[2].vx - pair.bodies.velocity[1].vx, 0.5, 1e-12);
}

TEST(Candidates, GentleClosureStopsAtContactWithoutRestitution)
{
  // At rest at the start, pushed together only by this step's force: the gap closes exactly
  // by the end of the step, with no rebound, whatever e is.
  const cd::StepParameters step{1e-3, 0.5};
  const double gap = 1e-5;
  PairNearContact pair = pair_near_contact(gap, 0.0, 0.5);
  cd::prepare_mechanics(pair.contact, pair.gap, {0.0, 1.0}, pair.bodies, step);
  std::vector<cd::Contact> contacts{pair.contact};
  cd::solve_gauss_seidel(contacts, pair.bodies.velocity, {1e-12, 100, cd::ConvergenceNorm::quadratic});
  const double u_n = cd::relative_velocity(contacts[0], pair.bodies.velocity[1], pair.bodies.velocity[2]).n;
  EXPECT_NEAR(cd::end_of_step_gap(gap, u_n, step), 0.0, 1e-15);
}

}  // namespace
