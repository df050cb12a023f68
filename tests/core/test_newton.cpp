// The semismooth Newton method on the contacts' problem (cd/newton_polish.h): one disk landing on
// a floor, sticking, sliding and lifting off, and two disks stacked on it, against their
// closed-form answers; the polish behind Gauss-Seidel against the sweeps alone on a stall step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cd/detection.h"
#include "cd/gauss_seidel.h"
#include "cd/newton_polish.h"
#include "cd/problem_file.h"
#include "pile.h"

namespace {

// A disk of mass m = 1 kg and inertia I = 1/2 kg m^2 (radius 1 m) on the floor y = 0, arriving at
// (vx, -1) m/s with no spin: W_nn = 1/m = 1, W_tt = 1/m + r^2/I = 3. The tangent is (-1, 0), so
// u_t = -vx before the impulses.
struct Landing {
  std::vector<cd::Contact> contacts;
  std::vector<cd::BodyVelocity> velocity;
};

Landing landing(double vx, double mu)
{
  Landing l;
  cd::BodySet bodies;
  bodies.reset(2);
  bodies.inertia[1] = {1.0, 2.0};
  bodies.start_velocity[1] = {vx, -1.0, 0.0};
  bodies.velocity = bodies.start_velocity;
  l.contacts = {cd::prepared_contact(cd::disk_world_geometry(1, cd::Disk{0.0, 1.0, 1.0}, 0.0, 0.0, 0.0, 1.0), {mu, 0.0},
                                     bodies, step)};
  l.velocity = bodies.velocity;
  return l;
}

// Sticking: p_n = 1 N s stops the fall, p_t = -u_t / W_tt = 0.1 / 3 stops the slip, inside the
// cone at mu = 0.5; the contact point at rest (the disk rolls: vx = -spin r).
TEST(SemismoothNewton, OneStickingContactInClosedForm)
{
  Landing l = landing(0.1, 0.5);
  const cd::NewtonSolve solve = cd::solve_newton(l.contacts, l.velocity);
  EXPECT_TRUE(solve.converged);
  EXPECT_LE(solve.iterations, 10);
  EXPECT_NEAR(l.contacts[0].impulse.n, 1.0, 1e-9);
  EXPECT_NEAR(l.contacts[0].impulse.t, 0.1 / 3.0, 1e-9);
  const cd::Local2 u = cd::law_velocity(l.contacts[0], l.velocity[1], l.velocity[0]);
  EXPECT_NEAR(u.n, 0.0, 1e-9);
  EXPECT_NEAR(u.t, 0.0, 1e-9);
}

// Sliding at mu = 0.01: p_n = 1, p_t = +mu p_n (u_t < 0 keeps its sign: -0.1 + 3 * 0.01 = -0.07).
TEST(SemismoothNewton, OneSlidingContactInClosedForm)
{
  Landing l = landing(0.1, 0.01);
  const cd::NewtonSolve solve = cd::solve_newton(l.contacts, l.velocity);
  EXPECT_TRUE(solve.converged);
  EXPECT_NEAR(l.contacts[0].impulse.n, 1.0, 1e-9);
  EXPECT_NEAR(l.contacts[0].impulse.t, 0.01, 1e-9);
  const cd::Local2 u = cd::law_velocity(l.contacts[0], l.velocity[1], l.velocity[0]);
  EXPECT_NEAR(u.n, 0.0, 1e-9);
  EXPECT_NEAR(u.t, -0.07, 1e-9);
  EXPECT_NEAR(cd::alart_curnier_residual_sq(l.contacts, l.velocity), 0.0, 1e-18);
}

// A disk lifting off (moving up at 1 m/s): no impulse, whatever the warm start says.
TEST(SemismoothNewton, AnOpeningContactDropsItsImpulse)
{
  Landing l = landing(0.1, 0.5);
  l.velocity[1].vy = 1.0;
  l.contacts[0].impulse = {0.3, 0.1};
  cd::apply_impulses(l.contacts, l.velocity);
  EXPECT_TRUE(cd::solve_newton(l.contacts, l.velocity).converged);
  EXPECT_NEAR(l.contacts[0].impulse.n, 0.0, 1e-9);
  EXPECT_NEAR(l.contacts[0].impulse.t, 0.0, 1e-9);
  EXPECT_NEAR(l.velocity[1].vy, 1.0, 1e-9);
}

// Two unit disks stacked on the floor, both falling at 1 m/s: the upper contact p = 1 N s, the
// floor's 2 N s, both at rest after; no tangential impulse.
TEST(SemismoothNewton, TwoStackedDisksComeToRest)
{
  cd::BodySet bodies;
  bodies.reset(3);
  for (int k : {1, 2}) {
    bodies.inertia[k] = {1.0, 2.0};
    bodies.start_velocity[k] = {0.0, -1.0, 0.0};
  }
  bodies.velocity = bodies.start_velocity;
  const cd::Disk lower{0.0, 1.0, 1.0}, upper{0.0, 3.0, 1.0};
  std::vector<cd::Contact> contacts{
      cd::prepared_contact(cd::disk_world_geometry(1, lower, 0.0, 0.0, 0.0, 1.0), {0.5, 0.0}, bodies, step),
      cd::prepared_contact(cd::disk_disk_geometry(2, upper, 1, lower), {0.5, 0.0}, bodies, step)};
  std::vector<cd::BodyVelocity> velocity = bodies.velocity;
  const cd::NewtonSolve solve = cd::solve_newton(contacts, velocity);
  EXPECT_TRUE(solve.converged);
  EXPECT_NEAR(contacts[0].impulse.n, 2.0, 1e-8);
  EXPECT_NEAR(contacts[1].impulse.n, 1.0, 1e-8);
  for (const cd::Contact& c : contacts) EXPECT_NEAR(c.impulse.t, 0.0, 1e-8);
  for (int k : {1, 2}) EXPECT_NEAR(velocity[k].vy, 0.0, 1e-8);
}

// The committed stall step at mu 2 (448 contacts), from its warm start to 1e-8: Gauss-Seidel with
// the polish keeps at least one polish and ends where the sweeps alone end, within what the
// tolerance admits. Velocities, not impulses: a loop of contacts leaves the impulses free by a
// self-stress.
TEST(NewtonPolish, TheStallStepEndsWhereTheSweepsAloneEnd)
{
  const cd::ContactProblem problem = cd::read_problem(std::string(CD_TEST_DATA) + "/peers/stall_mu2_e0.5_hard.cdp");
  cd::SolverSettings settings;
  settings.tolerance = 1e-8;
  settings.max_iterations = 200000;
  settings.gauss_seidel.acceleration = cd::Acceleration::conjugate;
  settings.gauss_seidel.full_sweep_every = 8;
  const auto solved = [&](bool polish, cd::SolveReport& report) {
    std::vector<cd::Contact> contacts = problem.contacts;
    std::vector<cd::BodyVelocity> velocity = problem.free_velocity;
    cd::apply_impulses(contacts, velocity);
    settings.gauss_seidel.newton_polish = polish;
    report = cd::solve_gauss_seidel(contacts, velocity, settings);
    return velocity;
  };
  cd::SolveReport alone, with;
  const std::vector<cd::BodyVelocity> plain = solved(false, alone), polished = solved(true, with);
  ASSERT_TRUE(alone.converged);
  ASSERT_TRUE(with.converged);
  EXPECT_GE(with.newton_polishes, 1);
  double change = 0.0;  // the largest velocity change the contacts make (m/s)
  for (std::size_t k = 0; k < plain.size(); k++)
    change = std::max({change, std::fabs(plain[k].vx - problem.free_velocity[k].vx),
                       std::fabs(plain[k].vy - problem.free_velocity[k].vy)});
  for (std::size_t k = 0; k < plain.size(); k++) {
    EXPECT_NEAR(polished[k].vx, plain[k].vx, 1e-5 * change) << k;
    EXPECT_NEAR(polished[k].vy, plain[k].vy, 1e-5 * change) << k;
  }
}

}  // namespace
