// LAMMPS regions as walls (wall region ID mu e) against cases with a known answer: a disk at
// rest in a circular cup, a disk rolling without slipping inside a turning drum, a grain thrown
// at a moving plane, a block's corner, and the walls' warm start across a restart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "atom.h"
#include "fix.h"
#include "fmt/format.h"
#include "lammps_session.h"

namespace {

using cdtest::LammpsSession;

constexpr double d = 1e-3, r = 0.5 * d;  // m
constexpr double g = 9.81;               // m/s^2
constexpr double density = 2500;         // kg/m^2 (density/disc)
const double mass = M_PI * r * r * density;

// One disk of diameter d in a closed square box of half-width `half` (m), its region and fix
// lines given by the test; `gravity`: whether it falls along -y.
void one_disk_deck(LammpsSession& s, double half, double x, double y, const std::string& region,
                   const std::string& fix_line, double dt, bool gravity)
{
  s.commands(cdtest::disk_preamble);
  s.commands(fmt::format(R"(
boundary f f p
region box block -{h} {h} -{h} {h} -{r} {r} units box
create_box 1 box
create_atoms 1 single {x} {y} 0 units box
set atom 1 diameter {d} density/disc {rho}
{region}
neighbor {skin} bin
timestep {dt}
{fix}
fix 2d all enforce2d
)",
                         fmt::arg("h", half), fmt::arg("r", r), fmt::arg("x", x), fmt::arg("y", y), fmt::arg("d", d),
                         fmt::arg("rho", density), fmt::arg("region", region), fmt::arg("skin", 0.2 * d),
                         fmt::arg("dt", dt), fmt::arg("fix", fix_line)));
  if (gravity) s.commands(fmt::format("fix grav all gravity {} vector 0 -1 0", g));
}

// Resting at the bottom of a circular cup (a sphere region, side in, centred on z = 0), a disk's
// one contact is the cup's (wall 1) at the cup's lowest point, and its normal impulse carries
// the weight over the step. The solve's tolerance (1e-12) bounds the impulse's error.
TEST(RegionWalls, ACupCarriesADiskAtRestAtItsBottom)
{
  const double cup = 5e-3, dt = 1e-5;
  LammpsSession s;
  one_disk_deck(s, 1e-2, 0.0, -(cup - r), fmt::format("region cup sphere 0 0 0 {} side in units box", cup),
                "fix cd all contact/dynamics 0.5 0.0 wall region cup 0.5 0.0 tolerance 1e-12", dt, true);
  s.commands("run 200");
  const LAMMPS_NS::Fix* fix = s.fix("cd");
  ASSERT_EQ(fix->size_local_rows, 1);
  const double* contact = fix->array_local[0];
  EXPECT_EQ(contact[1], 0.0);  // the second body: a wall
  EXPECT_EQ(contact[2], 1.0);  // wall 1
  EXPECT_NEAR(contact[3], mass * g * dt, 1e-9 * mass * g * dt);
  EXPECT_NEAR(contact[4], 0.0, 1e-12 * mass * g * dt);
  // The contact point, midway between the surfaces: the cup's bottom.
  EXPECT_NEAR(contact[5], 0.0, 1e-12);
  EXPECT_NEAR(contact[6], -cup, 1e-9 * d);
  EXPECT_NEAR(s.v(1, 0), 0.0, 1e-12);
  EXPECT_NEAR(s.v(1, 1), 0.0, 1e-12);
}

// The disk rolling without slipping inside a drum of radius R turning at Omega: its centre's
// angle phi from the bottom obeys (3/2)(R - r) phi'' = -g sin(phi) whatever Omega (the friction
// that keeps the contact sticking does no work in the drum's frame), and the contact's no-slip
// condition gives the spin, omega = (Omega R - (R - r) phi') / r.
struct RollingState {
  double phi, rate;  // rad, rad/s
};

RollingState rolling_pendulum(double phi0, double lever, double t)
{
  RollingState y{phi0, 0.0};
  const int n = 20000;
  const double h = t / n;
  const auto accel = [&](double phi) { return -2.0 * g * std::sin(phi) / (3.0 * lever); };
  for (int k = 0; k < n; k++) {  // classical Runge-Kutta: error far below the step's
    const RollingState k1{y.rate, accel(y.phi)};
    const RollingState k2{y.rate + 0.5 * h * k1.rate, accel(y.phi + 0.5 * h * k1.phi)};
    const RollingState k3{y.rate + 0.5 * h * k2.rate, accel(y.phi + 0.5 * h * k2.phi)};
    const RollingState k4{y.rate + h * k3.rate, accel(y.phi + h * k3.phi)};
    y.phi += h / 6.0 * (k1.phi + 2 * k2.phi + 2 * k3.phi + k4.phi);
    y.rate += h / 6.0 * (k1.rate + 2 * k2.rate + 2 * k3.rate + k4.rate);
  }
  return y;
}

struct DrumRun {
  double phi_error;   // largest |phi - analytic| over the run (rad)
  double spin_error;  // largest |spin - analytic| (rad/s)
};

// The drum turns counter-clockwise at Omega about its centre (region ... rotate), the disk starts
// at phi0 at rest with the spin of rolling, measured every `every` steps over one period.
DrumRun roll_in_drum(double omega_drum, double dt)
{
  const double drum = 5e-3, phi0 = 0.15, lever = drum - r;
  const double period = 2.0 * M_PI * std::sqrt(3.0 * lever / (2.0 * g));
  LammpsSession s;
  one_disk_deck(s, 1e-2, lever * std::sin(phi0), -lever * std::cos(phi0),
                fmt::format("variable turn equal {}*time\n"
                            "region drum cylinder z 0 0 {} INF INF side in units box rotate v_turn 0 0 0 0 0 1",
                            omega_drum, drum),
                "fix cd all contact/dynamics 0.5 0.0 wall region drum 0.5 0.0 tolerance 1e-12", dt, true);
  s.commands(fmt::format("set atom 1 omega 0 0 {}", omega_drum * drum / r));
  const int every = 100;
  const int samples = static_cast<int>(period / (every * dt));
  DrumRun run{0.0, 0.0};
  for (int k = 1; k <= samples; k++) {
    s.commands(fmt::format("run {} pre no post no", every));
    const double t = k * every * dt;
    const RollingState exact = rolling_pendulum(phi0, lever, t);
    const double phi = std::atan2(s.x(1, 0), -s.x(1, 1));
    run.phi_error = std::max(run.phi_error, std::fabs(phi - exact.phi));
    const double spin = (omega_drum * drum - lever * exact.rate) / r;
    run.spin_error = std::max(run.spin_error, std::fabs(s.spin(1) - spin));
  }
  return run;
}

// Over one period the scheme is first order in the step: the errors at 1e-5 s are about half
// those at 2e-5 s.
TEST(RegionWalls, ADiskRollsWithoutSlippingInATurningDrum)
{
  const double omega_drum = 2.0;  // rad/s
  const DrumRun fine = roll_in_drum(omega_drum, 1e-5);
  const DrumRun coarse = roll_in_drum(omega_drum, 2e-5);
  // Measured: 2.9e-6 rad and 1.05e-3 rad/s at 1e-5 s, twice that at 2e-5 s (of 0.15 rad and
  // 20 rad/s): bounds at 3x and 5x the measured, far below a static surface's error (the spin
  // would decay by slipping).
  EXPECT_LT(fine.phi_error, 1e-5);
  EXPECT_LT(fine.spin_error, 5e-3);
  EXPECT_NEAR(fine.phi_error / coarse.phi_error, 0.5, 0.1);
  EXPECT_NEAR(fine.spin_error / coarse.spin_error, 0.5, 0.1);
}

// A plane region moving along its normal at V (region ... move), hit head-on by a grain at u:
// Newton's restitution in the plane's frame sends it back at V - e (u - V).
TEST(RegionWalls, AGrainBouncesOffAMovingPlaneInItsFrame)
{
  const double plane_speed = 0.2, grain_speed = -0.5, e = 0.5;
  LammpsSession s;
  one_disk_deck(s, 1e-2, 3 * d, 0.0,
                fmt::format("variable travel equal {}*time\n"
                            "region piston plane 0 0 0 1 0 0 side in units box move v_travel NULL NULL",
                            plane_speed),
                fmt::format("fix cd all contact/dynamics 0.5 0.5 wall region piston 0.5 {} tolerance 1e-12", e), 1e-5,
                false);
  s.commands(fmt::format("velocity all set {} 0 0 units box", grain_speed));
  s.commands("run 1000");  // the impact comes after about 360 steps
  EXPECT_NEAR(s.v(1, 0), plane_speed - e * (grain_speed - plane_speed), 1e-9);
  EXPECT_NEAR(s.v(1, 1), 0.0, 1e-12);
  EXPECT_NEAR(s.spin(1), 0.0, 1e-9);
}

// In the corner of a block (side in) with gravity along the diagonal, a frictionless disk rests
// on two faces, each carrying m g dt / sqrt(2); the region is wall 2, after a line given first.
TEST(RegionWalls, ABlocksCornerHoldsADiskOnTwoFaces)
{
  const double corner = -5e-3, dt = 1e-5;
  LammpsSession s;
  one_disk_deck(s, 1e-2, corner + r, corner + r,
                fmt::format("region pen block {c} 5e-3 {c} 5e-3 INF INF side in units box", fmt::arg("c", corner)),
                "fix cd all contact/dynamics 0 0 wall xplane 9e-3 0 0 wall region pen 0 0 tolerance 1e-12", dt, false);
  s.commands(fmt::format("fix grav all gravity {} vector -1 -1 0", g));
  s.commands("run 100");
  const LAMMPS_NS::Fix* fix = s.fix("cd");
  ASSERT_EQ(fix->size_local_rows, 2);
  for (int row = 0; row < 2; row++) {
    const double* contact = fix->array_local[row];
    EXPECT_EQ(contact[2], 2.0);
    EXPECT_NEAR(contact[3], mass * g * dt / std::sqrt(2.0), 1e-9 * mass * g * dt);
  }
  EXPECT_NEAR(std::hypot(s.v(1, 0), s.v(1, 1)), 0.0, 1e-12);
}

// A pile in a turning drum: `run N`, write_restart, `run N` in one instance and in a new one
// from the file (the deck's regions and fixes given again) end bit for bit the same: the region
// walls' warm starts travel in the restart, their poses come from the variables.
TEST(RegionWalls, ATurningDrumContinuesBitwiseFromARestart)
{
  const std::string restart = "test_region_walls.restart";
  const std::string after_atoms = R"(
neigh_modify delay 0 every 1 check yes
comm_modify vel yes
variable turn equal 2.0*time
region drum cylinder z 0 0 5e-3 INF INF side in units box rotate v_turn 0 0 0 0 0 1
neighbor 2e-4 bin
timestep 1e-5
fix grav all gravity 9.81 vector 0 -1 0
fix cd all contact/dynamics 0.5 0.5 wall region drum 0.5 0.5 tolerance 1e-6
fix 2d all enforce2d
)";
  std::vector<double> one_instance, from_file;
  const auto state = [](const LammpsSession& s) {
    std::vector<double> values;
    for (int id = 1; id <= s.lmp->atom->natoms; id++)
      for (double value : {s.x(id, 0), s.x(id, 1), s.v(id, 0), s.v(id, 1), s.spin(id)}) values.push_back(value);
    return values;
  };
  {
    LammpsSession s;
    s.commands(cdtest::disk_preamble);
    s.commands(R"(
boundary f f p
region box block -6e-3 6e-3 -6e-3 6e-3 -5e-4 5e-4 units box
create_box 1 box
lattice sq 1.2e-3 origin 0.5 0.5 0
region start block -3e-3 3e-3 -3e-3 3e-3 INF INF units box
create_atoms 1 region start
set group all diameter 1e-3 density/disc 2500
)");
    s.commands(after_atoms);
    s.commands(fmt::format("run 2000\nwrite_restart {}\nrun 2000", restart));
    one_instance = state(s);
  }
  {
    LammpsSession s;
    s.commands("read_restart " + restart);
    s.commands(after_atoms);
    s.commands("run 2000");
    from_file = state(s);
  }
  std::remove(restart.c_str());
  ASSERT_GT(one_instance.size(), 100u);
  EXPECT_EQ(one_instance, from_file);
}

}  // namespace
