// The ways of needing fewer local solves: conjugate acceleration of the sweeps
// (SolverSettings::acceleration) and cycles that visit quiet contacts less often
// (SolverSettings::full_sweep_every). The same law at the end of a solve, and no more work than
// plain sweeps where they cannot help.
#include <gtest/gtest.h>

#include <cmath>

#include "cd/gauss_seidel.h"
#include "testbed/granular_bed.h"

namespace {

// The settled bed of 600 disks (src/testbed/granular_bed) the tests solve one step of.
const testbed::GranularBed& bed()
{
  static const testbed::GranularBed built([] {
    testbed::BedSpec spec;
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

Solved solve_step(bool warm, double tolerance, cd::Acceleration acceleration, int full_sweep_every = 1)
{
  const testbed::FrozenStep frozen = bed().freeze();
  Solved s{{}, {}, frozen.bodies.velocity};
  testbed::prepare_contacts(frozen, warm, s.contacts);
  cd::apply_impulses(s.contacts, s.velocity);
  cd::SolverSettings settings = bed().spec().solver;
  settings.tolerance = tolerance;
  settings.gauss_seidel.acceleration = acceleration;
  settings.gauss_seidel.full_sweep_every = full_sweep_every;
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
    const cd::Local2 u = cd::law_velocity(c, s.velocity[c.body_a], s.velocity[c.body_b]);
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

// Every impulse on its Coulomb cone.
void expect_on_their_cones(const Solved& s)
{
  for (const cd::Contact& c : s.contacts) {
    EXPECT_GE(c.impulse.n, 0.0);
    EXPECT_LE(std::abs(c.impulse.t), c.mu * c.impulse.n);
  }
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
  expect_on_their_cones(conjugate);
  std::printf("warm step of a settled bed: sweeps plain %d, conjugate %d; law residuals %.2g, %.2g\n", sweeps_plain,
              sweeps_conjugate, coulomb_residual(plain), coulomb_residual(conjugate));
}

// Cycles of a full sweep and active sweeps end only on a full sweep that meets the tolerance,
// so the law is met as closely as with plain sweeps; cold, the bed's contacts load one after
// the other, and the quiet ones skipped (every contact is updated fewer times than the
// sweeps made) save local solves with either kind of sweep.
TEST(QuietContacts, CyclesEndOnTheLawInFewerLocalSolves)
{
  for (const cd::Acceleration acceleration : {cd::Acceleration::none, cd::Acceleration::conjugate}) {
    const Solved full = solve_step(false, 1e-3, acceleration);
    const Solved cycles = solve_step(false, 1e-3, acceleration, 8);
    ASSERT_TRUE(full.report.converged);
    ASSERT_TRUE(cycles.report.converged);
    EXPECT_LE(cycles.report.residual, 1e-3);
    const double contacts = static_cast<double>(cycles.contacts.size());
    EXPECT_DOUBLE_EQ(full.report.contact_updates, full.report.iterations * contacts);
    EXPECT_LT(cycles.report.contact_updates, 0.9 * cycles.report.iterations * contacts) << "no contact was skipped";
    EXPECT_LT(cycles.report.contact_updates, full.report.contact_updates);
    EXPECT_LE(coulomb_residual(cycles), 2.0 * coulomb_residual(full));
    expect_on_their_cones(cycles);
    std::printf(
        "cold step of a settled bed (%s): local solves per contact %.1f in full sweeps, %.1f in cycles of 8 "
        "(%d sweeps); law residuals %.2g, %.2g\n",
        acceleration == cd::Acceleration::none ? "plain" : "conjugate", full.report.contact_updates / contacts,
        cycles.report.contact_updates / contacts, cycles.report.iterations, coulomb_residual(full),
        coulomb_residual(cycles));
  }
}

// A solve cut by the iteration cap between two full sweeps has not been checked by a full
// sweep: it is reported unconverged even when the active contacts met the tolerance.
TEST(QuietContacts, ACapBeforeTheFullSweepIsNotConvergence)
{
  const Solved free_run = solve_step(false, 1e-3, cd::Acceleration::none, 8);
  ASSERT_TRUE(free_run.report.converged);
  ASSERT_GT(free_run.report.iterations, 8);
  const testbed::FrozenStep frozen = bed().freeze();
  cd::SolverSettings settings = bed().spec().solver;
  settings.tolerance = 1e-3;
  settings.gauss_seidel.full_sweep_every = 8;
  settings.max_iterations = free_run.report.iterations - 1;  // the last sweep that checks is cut
  std::vector<cd::Contact> contacts;
  testbed::prepare_contacts(frozen, false, contacts);
  std::vector<cd::BodyVelocity> velocity = frozen.bodies.velocity;
  cd::apply_impulses(contacts, velocity);
  const cd::SolveReport cut = cd::solve_gauss_seidel(contacts, velocity, settings);
  EXPECT_EQ(cut.iterations, settings.max_iterations);
  EXPECT_LE(cut.residual, settings.tolerance) << "the last sweep should be an active one that met the tolerance";
  EXPECT_FALSE(cut.converged);
}

}  // namespace

namespace {

// A column of n disks (radius 0.5, mass 1) standing on a floor, each falling at g dt at the
// step's start from rest: every contact closes on the first sweep and then sticks without a
// tangential impulse, and the answer is the weight above each contact, p_k = (n - k) m g dt
// (k = 0 the floor's). Gauss–Seidel on it is the chain's linear iteration, slow in n.
struct Column {
  static constexpr int disks = 30;
  static constexpr double g = 9.81, dt = 1e-3;
  std::vector<cd::Contact> contacts;
  std::vector<cd::BodyVelocity> velocity;
};

Column make_column()
{
  constexpr double r = 0.5, m = 1.0;
  cd::BodySet bodies;
  bodies.reset(Column::disks + 1);
  Column column;
  for (int k = 1; k <= Column::disks; k++) {
    bodies.inertia[k] = {1.0 / m, 1.0 / (0.5 * m * r * r)};
    bodies.velocity[k] = {0.0, -Column::g * Column::dt, 0.0};
    const cd::ContactGeometry geometry =
        k == 1 ? cd::disk_world_geometry(1, cd::Disk{0, r, r}, 0.0, r, 0.0, 1.0)
               : cd::disk_disk_geometry(k, cd::Disk{0, (2 * k - 1) * r, r}, k - 1, cd::Disk{0, (2 * k - 3) * r, r});
    column.contacts.push_back(cd::prepared_contact(geometry, {0.5, 0.0}, bodies, {Column::dt, 0.5}));
  }
  column.velocity = bodies.velocity;
  return column;
}

cd::SolveReport solve_column(Column& column, double over_relaxation, int max_iterations)
{
  cd::SolverSettings settings{1e-10, max_iterations, cd::ConvergenceNorm::quadratic};
  settings.gauss_seidel.over_relaxation = over_relaxation;
  return cd::solve_gauss_seidel(column.contacts, column.velocity, settings);
}

// The largest error of the column's impulses against its answer, over the floor's impulse.
double column_error(const Column& column)
{
  const double floor_impulse = Column::disks * Column::g * Column::dt;
  double worst = 0.0;
  for (int k = 0; k < Column::disks; k++) {
    const cd::Contact& c = column.contacts[k];
    worst = std::max(worst, std::hypot(c.impulse.n - (Column::disks - k) * Column::g * Column::dt, c.impulse.t));
  }
  return worst / floor_impulse;
}

// On faces that stay put the local solves are linear, and over-relaxation is successive
// over-relaxation of the chain: the same answer in several times fewer sweeps (SOR's optimal w
// for this chain is near 1.8). The tolerance 1e-10 bounds the last sweep's change; the answer is
// within 1e-10 / (1 - rate) of it, rate the contraction of a sweep: under 1e-7 here.
TEST(OverRelaxation, SettledFacesReachTheAnswerInAFractionOfTheSweeps)
{
  Column plain = make_column(), over = make_column();
  const cd::SolveReport plain_report = solve_column(plain, 1.0, 100000);
  const cd::SolveReport over_report = solve_column(over, 1.8, 100000);
  ASSERT_TRUE(plain_report.converged);
  ASSERT_TRUE(over_report.converged);
  EXPECT_LT(column_error(plain), 1e-7);
  EXPECT_LT(column_error(over), 1e-7);
  EXPECT_LT(over_report.iterations, plain_report.iterations / 5);
  std::printf("column of %d disks to 1e-10: sweeps plain %d, over-relaxed by 1.8 %d; errors %.2g, %.2g\n",
              Column::disks, plain_report.iterations, over_report.iterations, column_error(plain), column_error(over));
}

// The first sweep closes every contact (a change of face): the second sweep is still plain, the
// third, after a sweep that changed no face, is the first over-relaxed.
TEST(OverRelaxation, WaitsForASweepThatChangesNoFace)
{
  for (const int sweeps : {2, 3}) {
    Column plain = make_column(), over = make_column();
    solve_column(plain, 1.0, sweeps);
    solve_column(over, 1.8, sweeps);
    bool same = true;
    for (int k = 0; k < Column::disks; k++)
      same = same && plain.contacts[k].impulse.n == over.contacts[k].impulse.n &&
             plain.contacts[k].impulse.t == over.contacts[k].impulse.t;
    EXPECT_EQ(same, sweeps == 2) << "after " << sweeps << " sweeps";
  }
}

// On the settled bed, where faces change in the first sweeps and sliding contacts meet the cone,
// over-relaxed sweeps end as close to the law as plain ones, every impulse put back on its cone.
TEST(OverRelaxation, EndsOnTheLawOnASettledBed)
{
  const Solved plain = solve_step(true, 1e-4, cd::Acceleration::none);
  const testbed::FrozenStep frozen = bed().freeze();
  Solved over{{}, {}, frozen.bodies.velocity};
  testbed::prepare_contacts(frozen, true, over.contacts);
  cd::apply_impulses(over.contacts, over.velocity);
  cd::SolverSettings settings = bed().spec().solver;
  settings.tolerance = 1e-4;
  settings.gauss_seidel.over_relaxation = 1.8;
  over.report = cd::solve_gauss_seidel(over.contacts, over.velocity, settings);
  ASSERT_TRUE(over.report.converged);
  EXPECT_LE(coulomb_residual(over), 2.0 * coulomb_residual(plain));
  expect_on_their_cones(over);
  std::printf("warm step of a settled bed to 1e-4: sweeps plain %d, over-relaxed %d; law residuals %.2g, %.2g\n",
              plain.report.iterations, over.report.iterations, coulomb_residual(plain), coulomb_residual(over));
}

}  // namespace
