// max_iterations caps the sweeps of one solve; output 1 counts the sweeps of every solve of the
// step (a step solves again when a pair the first solve left out would overlap).
#include <gtest/gtest.h>

#include "lammps_session.h"

namespace {

using cdtest::LammpsSession;

// Two disks of d = 0.5 mm falling at 3 m/s in a column, the lower one 0.02 d above the floor,
// the upper one 0.02 d above it. In step 1 the floor is a candidate (its gap closes within the
// step); the pair is not (both fall alike, and 0.02 d is above the alert distance given, 0.01 d).
// The first solve stops the lower disk (e = 0); the upper one, still falling 1.5e-5 m in half a
// step, would overlap it by 0.01 d: the pair joins and the step solves again.
TEST(IterationCap, CapsEachSolveOfAStepNotTheStep)
{
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  s.commands(R"(
boundary p f p
region box block 0 0.01 0 0.01 -0.0003 0.0003
create_box 1 box
create_atoms 1 single 0.005 0.00026 0
create_atoms 1 single 0.005 0.00077 0
set group all diameter 5e-4 density/disc 2500
velocity all set 0 -3 0 units box
neighbor 1e-4 bin
timestep 1e-5
fix cd all contact/dynamics 0.5 0.0 max_iterations 1 alert 5e-6 wall yplane 0.0 0.5 0.0
run 1
)");
  LAMMPS_NS::Fix* fix = s.fix("cd");
  EXPECT_EQ(fix->compute_vector(2), 2.0);   // contacts solved: the floor, then the pair
  EXPECT_EQ(fix->compute_vector(0), 2.0);   // sweeps this step: one per solve, twice the cap
  EXPECT_EQ(fix->compute_vector(11), 2.0);  // solves this step: the first, and again for the pair
  EXPECT_EQ(fix->compute_vector(6), 0.0);   // the last solve stopped at the cap
  EXPECT_EQ(fix->compute_vector(8), 1.0);   // one step hit the cap
}

}  // namespace
