// Conjugate acceleration of the sweeps (SolverSettings::acceleration): the same law at the
// end of a solve, and no more sweeps than plain ones where it cannot help.
#include <gtest/gtest.h>

#include <cmath>

#include "cd/gauss_seidel.h"
#include "granular_bed.h"

namespace {

// The settled bed of 600 disks (bench/granular_bed) the tests solve one step of.
const bench::GranularBed& bed()
{
  static const bench::GranularBed built([] {
    bench::BedSpec spec;
    spec.disk_count = 600;
    spec.cell_length = 20.0;
    return spec;
  }());
  return built;
}

struct Solved {
  cd::SolveReport report;
  std::vector<cd::Contact> contacts;
  std::vector<cd::BodyVelocity> velocity;
};

Solved solve_step(bool warm, double tolerance, cd::Acceleration acceleration)
{
  const bench::FrozenStep frozen = bed().freeze();
  Solved s{{}, {}, frozen.bodies.velocity};
  bench::prepare_contacts(frozen, warm, s.contacts);
  cd::apply_impulses(s.contacts, s.velocity);
  cd::SolverSettings settings = bed().spec().solver;
  settings.tolerance = tolerance;
  settings.acceleration = acceleration;
  s.report = cd::solve_gauss_seidel(s.contacts, s.velocity, settings);
  return s;
}

// Largest natural-map residual of the Coulomb–Signorini law over the contacts, in impulses
// and velocities each divided by its largest value over the bed (dimensionless; zero exactly
// when every contact obeys the law).
double coulomb_residual(const Solved& s)
{
  double impulse_scale = 0.0, velocity_scale = 0.0;
  std::vector<cd::Local2> velocities;
  for (const cd::Contact& c : s.contacts) {
    cd::Local2 u = cd::relative_velocity(c, s.velocity[c.body_a], s.velocity[c.body_b]);
    u.n += c.velocity_bias;
    velocities.push_back(u);
    impulse_scale = std::max(impulse_scale, std::hypot(c.impulse.n, c.impulse.t));
    velocity_scale = std::max(velocity_scale, std::hypot(u.n, u.t));
  }
  double worst = 0.0;
  for (std::size_t k = 0; k < s.contacts.size(); k++) {
    const cd::Contact& c = s.contacts[k];
    const cd::Local2 p{c.impulse.n / impulse_scale, c.impulse.t / impulse_scale};
    const cd::Local2 u{velocities[k].n / velocity_scale, velocities[k].t / velocity_scale};
    worst = std::max(worst, std::sqrt(cd::natural_map_residual_squared(p, u, c.mu)));
  }
  return worst;
}

// One step of a settled bed, warm-started from the previous one, at tolerance 1e-4. Plain
// sweeps creep to the tolerance, and accelerated ones must switch themselves off rather than
// disturb that (without the switch: several times the plain sweeps). Both end as close to
// the Coulomb–Signorini law, and the accelerated impulses lie on their cones (each pushed
// impulse is put back).
TEST(ConjugateAcceleration, EndsOnTheLawInNoMoreSweepsOnASettledBed)
{
  const Solved plain = solve_step(true, 1e-4, cd::Acceleration::none);
  const Solved conjugate = solve_step(true, 1e-4, cd::Acceleration::conjugate);
  ASSERT_TRUE(plain.report.converged);
  ASSERT_TRUE(conjugate.report.converged);
  const int sweeps_plain = plain.report.iterations, sweeps_conjugate = conjugate.report.iterations;
  EXPECT_GE(sweeps_plain, 10) << "the plain solve must creep for the test to mean something";
  EXPECT_LE(sweeps_conjugate, sweeps_plain + 3);
  EXPECT_LT(coulomb_residual(plain), 1e-5);
  EXPECT_LE(coulomb_residual(conjugate), 2.0 * coulomb_residual(plain));
  for (const cd::Contact& c : conjugate.contacts) {
    EXPECT_GE(c.impulse.n, 0.0);
    EXPECT_LE(std::abs(c.impulse.t), c.mu * c.impulse.n);
  }
  std::printf("warm step of a settled bed: sweeps plain %d, conjugate %d; law residuals %.2g, %.2g\n", sweeps_plain,
              sweeps_conjugate, coulomb_residual(plain), coulomb_residual(conjugate));
}

}  // namespace
