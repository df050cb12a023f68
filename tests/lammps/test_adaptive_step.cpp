// The step that follows the flow (fix contact/dynamics dt_max): a grain falling freely under
// gravity, v = g t exactly, so the level the fix must take at each alignment time is known.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "atom.h"
#include "fix.h"
#include "lammps_session.h"
#include "update.h"

namespace {

using cdtest::LammpsSession;

constexpr double dt_max = 1e-4;  // s
constexpr double align = 1e-3;   // s
constexpr double skin = 1e-4;    // m
constexpr double travel = 0.4;   // of the skin
constexpr double gravity = 9.81;

// Gravity and the fix with its step grid; thermo without temperature, whose degrees of freedom
// one grain would leave negative.
const char* integration = R"(
neighbor 1e-4 bin
timestep 1e-4
fix grav all gravity 9.81 vector 0 -1 0
fix cd all contact/dynamics 0.5 0.5 wall yplane 0.0 0.5 0.5 dt_max 1e-4 dt_align 1e-3 travel 0.4
fix 2d all enforce2d
thermo_style custom step time
run 0 post no
)";

void falling_grain(LammpsSession& s)
{
  s.commands(cdtest::disk_preamble);
  s.commands(R"(
boundary p f p
region box block 0 0.01 0 2.0 -0.0003 0.0003
create_box 1 box
create_atoms 1 single 0.005 1.9 0
set group all diameter 5e-4 density/disc 2500
)");
  s.commands(integration);
}

double lammps_time(const LammpsSession& s)
{
  const auto* u = s.lmp->update;
  return u->atime + static_cast<double>(u->ntimestep - u->atimestep) * u->dt;
}

// The level the grid must take at speed v: the smallest k with v dt_max / 2^k <= travel skin.
int expected_level(double speed)
{
  int level = 0;
  while (speed * dt_max / std::ldexp(1.0, level) > travel * skin) ++level;
  return level;
}

struct StepRecord {
  double time, dt, vy;
};

std::vector<StepRecord> run_steps(LammpsSession& s, int steps)
{
  std::vector<StepRecord> records;
  for (int k = 0; k < steps; k++) {
    s.commands("run 1 pre no post no");
    records.push_back({lammps_time(s), s.lmp->update->dt, s.v(1, 1)});
  }
  return records;
}

TEST(AdaptiveStep, FallingGrainTakesTheLevelOfItsSpeedAtEveryAlignmentTime)
{
  LammpsSession s;
  falling_grain(s);
  double time = 0.0, previous_dt = s.lmp->update->dt;
  EXPECT_EQ(previous_dt, dt_max) << "at rest: the largest step";
  const std::vector<StepRecord> records = run_steps(s, 3000);
  int changes = 0, aligned = 0;
  for (const StepRecord& r : records) {
    time += previous_dt;
    EXPECT_NEAR(r.time, time, 1e-12) << "LAMMPS time is the sum of the steps";
    EXPECT_NEAR(r.vy, -gravity * time, 1e-9) << "free fall";
    const double periods = time / align;
    const bool on_alignment = std::abs(periods - std::round(periods)) < 1e-9;
    if (on_alignment) {
      ++aligned;
      EXPECT_DOUBLE_EQ(r.dt, std::ldexp(dt_max, -expected_level(std::abs(r.vy)))) << "t = " << time;
    } else {
      EXPECT_EQ(r.dt, previous_dt) << "the step changed between alignment times, t = " << time;
    }
    if (r.dt != previous_dt) ++changes;
    previous_dt = r.dt;
  }
  EXPECT_GE(changes, 2) << "the fall crosses at least two levels";
  EXPECT_GT(aligned, 50);
  EXPECT_GT(time, 0.1);
}

// A restart written in the middle of an alignment period continues the same steps and clock.
TEST(AdaptiveStep, RestartContinuesTheLevelPositionAndTime)
{
  const std::string file = "test_adaptive_step.restart";
  LammpsSession first;
  falling_grain(first);
  run_steps(first, 1237);  // a little over 0.05 s, in the middle of a period at level > 0
  first.commands("write_restart " + file);
  const std::vector<StepRecord> straight_on = run_steps(first, 400);

  LammpsSession second;
  second.commands("read_restart " + file);
  second.commands("comm_modify vel yes\nneigh_modify delay 0 every 1 check yes");
  second.commands(integration);
  const std::vector<StepRecord> restarted = run_steps(second, 400);
  std::remove(file.c_str());
  for (std::size_t k = 0; k < restarted.size(); k++) {
    EXPECT_EQ(restarted[k].dt, straight_on[k].dt) << "step " << k;
    EXPECT_NEAR(restarted[k].time, straight_on[k].time, 1e-12) << "step " << k;
    EXPECT_EQ(restarted[k].vy, straight_on[k].vy) << "step " << k;
  }
  EXPECT_LT(straight_on.front().dt, dt_max) << "the restart was written at a refined level";
}

}  // namespace
