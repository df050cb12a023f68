// Obstacles (atoms outside the fix's group) moved by fix move, met at the grains' instant x_m: a
// conveyor floor carries a pile at its speed, a wall of obstacle atoms pushes a row of disks at
// its speed, and the grains overlap them at the end of each step no more than at rest, but for
// the Moreau-Jean scheme's own lag (1 - theta) dt dv when an obstacle speeds a grain up by dv.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>

#include "domain.h"
#include "fmt/format.h"
#include "group.h"
#include "lammps_session.h"

namespace {

using cdtest::LammpsSession;

constexpr double d = 5e-4, r = 0.5 * d, g = 9.81;
constexpr int floor_disks = 20;  // the conveyor: a row of touching disks filling the periodic cell
constexpr double cell = floor_disks * d;
const double row_height = std::sqrt(3.0) / 2.0 * d;

// The deck's lines after the atoms: disk sizes, the step, gravity, the fix (mu 0.5, e 0), 2D.
void finish_deck(LammpsSession& s, double dt, double theta, double tolerance, const std::string& walls)
{
  s.commands(fmt::format(R"(
set group all diameter {d} density/disc 2500
group grains subtract all obstacles
neighbor {skin} bin
timestep {dt}
fix grav grains gravity {g} vector 0 -1 0
fix cd grains contact/dynamics 0.5 0.0 theta {theta} tolerance {tolerance} max_iterations 100000 {walls}
fix 2d all enforce2d
)",
                         fmt::arg("d", d), fmt::arg("skin", 0.2 * d), fmt::arg("dt", dt), fmt::arg("g", g),
                         fmt::arg("walls", walls), fmt::arg("theta", theta), fmt::arg("tolerance", tolerance)));
}

// Disks in a square box of side `cell`, fixed along y, with x boundaries `x_boundary`.
void open_deck(LammpsSession& s, const char* x_boundary)
{
  s.commands(cdtest::disk_preamble);
  s.commands(fmt::format("boundary {x} f p\nregion box block 0 {L} 0 {L} -{r} {r}\ncreate_box 1 box",
                         fmt::arg("x", x_boundary), fmt::arg("L", cell), fmt::arg("r", r)));
}

// The conveyor's step: its start takes a few thousand steps at the higher speed. Its tolerance
// is looser (the pile's solves hit the cap at 1e-8 as it speeds up): its pile at rest overlaps
// by 2e-10 d.
constexpr double conveyor_dt = 5e-5, pusher_dt = 1e-5;

// A floor of obstacle disks (atoms 1-20) centred at y = r, and on it a triangular pile of 6, 5
// and 4 touching grains, each row in the hollows of the one below.
void conveyor_deck(LammpsSession& s, double theta)
{
  open_deck(s, "p");
  for (int k = 0; k < floor_disks; k++) s.commands(fmt::format("create_atoms 1 single {} {} 0", (k + 0.5) * d, r));
  s.commands(fmt::format("group obstacles id 1:{}", floor_disks));
  for (int row = 1; row <= 3; row++)
    for (int k = 0; k < 7 - row; k++)
      s.commands(fmt::format("create_atoms 1 single {} {} 0", (k + 0.5 + 0.5 * row) * d, r + row * row_height));
  finish_deck(s, conveyor_dt, theta, 1e-6, "");
}

// A floor y = 0 (mu 0.5), a column of four obstacle disks (atoms 1-4) at x = 2d and, 0.2 d ahead
// of it, a row of three touching grains resting on the floor.
void pusher_deck(LammpsSession& s, double theta)
{
  open_deck(s, "f");
  for (int k = 0; k < 4; k++) s.commands(fmt::format("create_atoms 1 single {} {} 0", 2 * d - 0.2 * d, r + k * d));
  s.commands("group obstacles id 1:4");
  for (int k = 1; k <= 3; k++) s.commands(fmt::format("create_atoms 1 single {} {} 0", (2 + k) * d, r));
  finish_deck(s, pusher_dt, theta, 1e-8, "wall yplane 0.0 0.5 0.0");
}

bool is_obstacle(const LammpsSession& s, int i)
{
  return (s.lmp->atom->mask[i] & s.lmp->group->bitmask[s.lmp->group->find("obstacles")]) != 0;
}

// Deepest overlap between a grain and any other atom or the floor y = 0 (if `floor_wall`), from
// the atoms' positions now (nearest periodic image along x), in diameters.
double deepest_overlap(const LammpsSession& s, bool floor_wall)
{
  const LAMMPS_NS::Atom* atom = s.lmp->atom;
  const bool periodic = s.lmp->domain->xperiodic != 0;
  double deepest = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (is_obstacle(s, i)) continue;
    if (floor_wall) deepest = std::max(deepest, atom->radius[i] - atom->x[i][1]);
    for (int j = 0; j < atom->nlocal; j++) {
      if (j == i) continue;
      double dx = atom->x[i][0] - atom->x[j][0];
      if (periodic) dx -= cell * std::round(dx / cell);
      const double dy = atom->x[i][1] - atom->x[j][1];
      deepest = std::max(deepest, atom->radius[i] + atom->radius[j] - std::hypot(dx, dy));
    }
  }
  return deepest / d;
}

struct Window {
  double deepest = 0.0;        // largest deepest_overlap over the steps (d)
  double shallowest = 1e300;   // smallest one (d)
  double output_mismatch = 0;  // largest |output 5 - deepest_overlap| over the steps (d)
};

// Runs `steps` steps one at a time, measuring after each what a user measures at its end.
Window measure_steps(LammpsSession& s, int steps, bool floor_wall)
{
  Window window;
  for (int step = 0; step < steps; step++) {
    s.commands("run 1 pre no post no");
    const double measured = deepest_overlap(s, floor_wall);
    window.deepest = std::max(window.deepest, measured);
    window.shallowest = std::min(window.shallowest, measured);
    window.output_mismatch = std::max(window.output_mismatch, std::fabs(s.fix("cd")->compute_vector(4) - measured));
  }
  return window;
}

double mean_grain_velocity(const LammpsSession& s, int axis)
{
  const LAMMPS_NS::Atom* atom = s.lmp->atom;
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (!is_obstacle(s, i)) {
      sum += atom->v[i][axis];
      count++;
    }
  return sum / count;
}

double largest_grain_speed_offset(const LammpsSession& s, double vx)
{
  const LAMMPS_NS::Atom* atom = s.lmp->atom;
  double largest = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (!is_obstacle(s, i)) largest = std::max(largest, std::hypot(atom->v[i][0] - vx, atom->v[i][1]));
  return largest;
}

constexpr int measured_steps = 50;
// Overlaps this small are the solves' tolerance (1e-6 and 1e-8 here), not the kinematics: a
// misplaced obstacle or the scheme's lag make 1e-4 d and more in these decks.
constexpr double solve_noise = 1e-8;  // d
// Output 5 and the test's own measure are the same sums in another order.
constexpr double same_measure = 1e-12;  // d

// The same deck with its obstacles at rest: the overlap level a moving obstacle must not exceed.
template <class Deck>
Window static_window(Deck deck, double theta, int steps, bool floor_wall)
{
  LammpsSession s;
  deck(s, theta);
  s.commands(fmt::format("run {}", steps));
  return measure_steps(s, measured_steps, floor_wall);
}

// The conveyor starts at a constant acceleration of g/2 up to `speed` (x = a t^2 / 2, then
// speed (t - t_ramp / 2)): a grain in a hollow of touching disks follows the hollow up to
// a = g / sqrt(3) without friction, so the pile is carried as one body.
constexpr double ramp_acceleration = 0.5 * g;

void start_conveyor(LammpsSession& s, double speed)
{
  s.commands(fmt::format(R"deck(
variable ramp equal {t_ramp}
variable late equal "(time-v_ramp)*(time>v_ramp)"
variable early equal "time-v_late"
variable shift equal "{a}*0.5*v_early^2+{V}*v_late"
variable speed equal "{a}*v_early"
fix conveyor obstacles move variable v_shift NULL NULL v_speed NULL NULL
)deck",
                         fmt::arg("t_ramp", speed / ramp_acceleration), fmt::arg("a", ramp_acceleration),
                         fmt::arg("V", speed)));
}

struct Motion {
  double speed;  // m/s
  double theta;
};

void PrintTo(const Motion& motion, std::ostream* os)
{
  *os << motion.speed << " m/s, theta " << motion.theta;
}

class MovingObstacles : public ::testing::TestWithParam<double> {};

// Floor and pile set off together at V: the pile rides the conveyor, its contacts sticking.
// Met at their end-of-step positions, the floor's disks left the grains overlapping them by
// 1e-3 d (0.05 m/s) and 9e-3 d (0.5 m/s) at the end of every step.
TEST_P(MovingObstacles, ConveyorCarriesAPileAtItsSpeedWithoutOverlap)
{
  const double speed = GetParam(), theta = 0.5;
  const int steps = 200;
  const Window at_rest = static_window(conveyor_deck, theta, steps, false);
  LammpsSession s;
  conveyor_deck(s, theta);
  s.commands(fmt::format("velocity grains set {} 0 0", speed));
  s.commands(fmt::format("fix conveyor obstacles move linear {} 0 0", speed));
  s.commands(fmt::format("run {}", steps));
  const Window moving = measure_steps(s, measured_steps, false);
  EXPECT_LT(largest_grain_speed_offset(s, speed), 1e-6 * speed);
  EXPECT_LE(moving.deepest, at_rest.deepest + solve_noise) << "at rest " << at_rest.deepest;
  EXPECT_LT(moving.output_mismatch, same_measure) << "output 5 measures the end-of-step overlap";
}

// A wall of obstacle atoms moving at V reaches a row of grains on a frictional floor: it strikes
// the first (e = 0), friction slows the row, and the wall catches up and pushes it at V, in
// contact. Met at its end-of-step position, the wall pushed the row from theta dt V away (5e-4 d
// at 0.05 m/s). The grains the wall catches up with had slowed, by less than V: they are sped up
// from a closed contact and lag by (1 - theta) dt dv, at most (1 - theta) dt V.
class PushingWall : public ::testing::TestWithParam<Motion> {};

TEST_P(PushingWall, PushesARowAtItsSpeedInContact)
{
  const Motion motion = GetParam();
  const int steps = 400;
  const Window at_rest = static_window(pusher_deck, motion.theta, steps, true);
  LammpsSession s;
  pusher_deck(s, motion.theta);
  s.commands(fmt::format("fix pusher obstacles move linear {} 0 0", motion.speed));
  s.commands(fmt::format("run {}", steps));
  const Window moving = measure_steps(s, measured_steps, true);
  EXPECT_LT(largest_grain_speed_offset(s, motion.speed), 1e-6 * motion.speed);
  // In contact: the first grain one diameter ahead of the wall's column.
  EXPECT_LE((s.x(5, 0) - s.x(1, 0)) / d - 1.0, solve_noise);
  const double lag = (1.0 - motion.theta) * pusher_dt * motion.speed / d;
  EXPECT_LE(moving.deepest, at_rest.deepest + lag + solve_noise) << "at rest " << at_rest.deepest;
  EXPECT_LT(moving.output_mismatch, same_measure) << "output 5 measures the end-of-step overlap";
}

// The conveyor speeds up from rest (start_conveyor) under a pile at rest, which it carries to its
// speed. Each step the floor adds dv to the speed of grains it holds in sticking contacts that
// are closed at x_m: they lag by (1 - theta) dt dv (their x_m is reached at the speed they had),
// which adds up to (1 - theta) dt V along the floor, (1 - theta) dt V cos 60 deg into the
// contacts behind them, and then stays: it does not grow at constant speed. At theta = 1: none.
class DrivenConveyor : public ::testing::TestWithParam<Motion> {};

TEST_P(DrivenConveyor, CarriesAPileFromRestToItsSpeed)
{
  const Motion motion = GetParam();
  // The speed-up, then as many steps again at full speed.
  const int steps = static_cast<int>(std::ceil(2.0 * motion.speed / ramp_acceleration / conveyor_dt));
  const Window at_rest = static_window(conveyor_deck, motion.theta, steps, false);
  LammpsSession s;
  conveyor_deck(s, motion.theta);
  start_conveyor(s, motion.speed);
  s.commands(fmt::format("run {}", steps));
  const Window moving = measure_steps(s, measured_steps, false);
  EXPECT_NEAR(mean_grain_velocity(s, 0), motion.speed, 1e-6 * motion.speed);
  EXPECT_LT(largest_grain_speed_offset(s, motion.speed), 1e-6 * motion.speed);
  const double lag = (1.0 - motion.theta) * conveyor_dt * motion.speed * 0.5 / d;
  EXPECT_NEAR(moving.deepest, at_rest.deepest + lag, 0.02 * lag + solve_noise) << "at rest " << at_rest.deepest;
  EXPECT_LE(moving.deepest - moving.shallowest, solve_noise) << "the lag does not grow at constant speed";
  EXPECT_LT(moving.output_mismatch, same_measure) << "output 5 measures the end-of-step overlap";
}

INSTANTIATE_TEST_SUITE_P(Speeds, MovingObstacles, ::testing::Values(0.05, 0.5));
const auto motions = ::testing::Values(Motion{0.05, 0.5}, Motion{0.5, 0.5}, Motion{0.05, 1.0}, Motion{0.5, 1.0});
INSTANTIATE_TEST_SUITE_P(SpeedsAndThetas, PushingWall, motions);
INSTANTIATE_TEST_SUITE_P(SpeedsAndThetas, DrivenConveyor, motions);

}  // namespace
