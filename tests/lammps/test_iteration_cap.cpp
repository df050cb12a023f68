// max_iterations caps the sweeps of one solve; output 1 counts the sweeps of every solve of the
// step (a step solves again when a pair the first solve left out would overlap).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "cd/problem_file.h"

#include "lammps_session.h"

namespace {

using cdtest::LammpsSession;

// Two disks of d = 0.5 mm falling at 3 m/s in a column (no fix yet).
constexpr const char* falling_column = R"(
boundary p f p
region box block 0 0.01 0 0.01 -0.0003 0.0003
create_box 1 box
create_atoms 1 single 0.005 0.00026 0
create_atoms 1 single 0.005 0.00077 0
set group all diameter 5e-4 density/disc 2500
velocity all set 0 -3 0 units box
neighbor 1e-4 bin
timestep 1e-5
)";

// Two disks of d = 0.5 mm falling at 3 m/s in a column, the lower one 0.02 d above the floor,
// the upper one 0.02 d above it. In step 1 the floor is a candidate (its gap closes within the
// step); the pair is not (both fall alike, and 0.02 d is above the alert distance given, 0.01 d).
// The first solve stops the lower disk (e = 0); the upper one, still falling 1.5e-5 m in half a
// step, would overlap it by 0.01 d: the pair joins and the step solves again.
TEST(IterationCap, CapsEachSolveOfAStepNotTheStep)
{
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  s.commands(falling_column);
  s.commands("fix cd all contact/dynamics 0.5 0.0 max_iterations 1 alert 5e-6 wall yplane 0.0 0.5 0.0\nrun 1");
  LAMMPS_NS::Fix* fix = s.fix("cd");
  EXPECT_EQ(fix->compute_vector(2), 2.0);   // contacts solved: the floor, then the pair
  EXPECT_EQ(fix->compute_vector(0), 2.0);   // sweeps this step: one per solve, twice the cap
  EXPECT_EQ(fix->compute_vector(11), 2.0);  // solves this step: the first, and again for the pair
  EXPECT_EQ(fix->compute_vector(6), 0.0);   // the last solve stopped at the cap
  EXPECT_EQ(fix->compute_vector(8), 1.0);   // one step hit the cap
}

// The same step with save_problems 0: the run ends with the fix's solver line (one step, at the
// cap), and the step's problem as its first solve met it (the floor contact alone: the pair
// joined later) is written where asked and reads back.
TEST(IterationCap, TheRunEndsWithItsSolverLineAndSavesTheStepAtTheCap)
{
  const std::string log = ::testing::TempDir() + "iteration_cap.log";
  const std::string prefix = ::testing::TempDir() + "cap";
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  s.commands("log " + log);
  s.commands(falling_column);
  s.commands("fix cd all contact/dynamics 0.5 0.0 max_iterations 1 alert 5e-6 save_problems 0 " + prefix +
             " wall yplane 0.0 0.5 0.0");
  s.commands("run 1\nlog none");
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Fix contact/dynamics cd solver: 1 steps, 1 unconverged (100 %), largest final norm "),
            std::string::npos)
      << text;
  EXPECT_NE(
      text.find(
          "sweeps per step median 2, 99th percentile 2, max 2, 0 rescued from a stall (0 started again from zero, 0 by "
          "exact block solves)"),
      std::string::npos);
  const cd::ContactProblem problem = cd::read_problem(prefix + ".1.cdp");
  ASSERT_EQ(problem.contacts.size(), 1u);
  EXPECT_EQ(problem.contacts[0].body_b, 0) << "the floor";
  EXPECT_EQ(problem.free_velocity.size(), 3u) << "the world and two disks";
  EXPECT_NEAR(problem.height[problem.contacts[0].body_a], 0.00026 - 0.5 * 1e-5 * 3.0, 1e-12) << "y at x_m";
  EXPECT_NE(problem.label.find("sweeps 2 converged 0"), std::string::npos) << problem.label;
  std::remove(log.c_str());
  std::remove((prefix + ".1.cdp").c_str());
}

}  // namespace
