// Decks that insert grains during a run and that clear LAMMPS between two runs.
#include <gtest/gtest.h>

#include <string>

#include "lmp_cd_run.h"

namespace {

using cdtest::error_line;
using cdtest::run_deck;
using cdtest::RunResult;

// 300 grains of 0.4-0.6 mm poured into a 20 x 18 d region: fix pour asks for 79 in its first
// wave and places fewer (the region is crowded), the case that overruns an array atom map.
std::string pour_deck(const std::string& map)
{
  return R"(
units si
dimension 2
atom_style sphere
atom_modify map )" +
         map + R"deck(
comm_modify vel yes
neigh_modify delay 0
boundary p f p
region box block 0 0.01 0 0.02 -0.0003 0.0003
create_box 1 box
region pour block 0 0.01 0.01 0.019 -0.0003 0.0003 units box
neighbor 1e-4 bin
timestep 1e-5
fix grav all gravity 9.81 vector 0 -1 0
fix pour all pour 300 1 4242 region pour diam range 4e-4 6e-4 dens 2500 2500
fix cd all contact/dynamics 0.5 0.5 density 2500 wall yplane 0.0 0.5 0.5
fix 2d all enforce2d
run 300
print "GRAINS $(count(all))"
)deck";
}

TEST(Pour, RunsWithAHashAtomMapWhenAnInsertionFallsShort)
{
  const RunResult result = run_deck("pour_hash", pour_deck("hash"));
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_EQ(error_line(result.output), "") << result.output;
  EXPECT_NE(result.output.find("Less insertions than requested"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("\nGRAINS "), std::string::npos) << result.output;
}

// The map the fix asks for is the one above; an array map (or `map yes`, an array below a
// million IDs) with fix pour is refused before the run instead of crashing in it.
TEST(Pour, RefusesAnArrayAtomMapInOneLine)
{
  for (const std::string map : {"array", "yes"}) {
    const RunResult result = run_deck("pour_" + map, pour_deck(map));
    EXPECT_EQ(result.exit_status >> 8, 1) << map << ": " << result.output;  // exit(1), not a signal
    EXPECT_NE(error_line(result.output)
                  .find("fix pour (pour) crashes this LAMMPS with an array atom map (map array or yes) when an "
                        "insertion falls short; use atom_modify map hash"),
              std::string::npos)
        << map << ": " << result.output;
  }
}

const std::string two_grains_run =
    cdtest::two_grains + "fix cd all contact/dynamics 0.5 0.5 wall yplane 0.0 0.5 0.5\nrun 10\n";

TEST(Clear, TheStylesSurviveIt)
{
  const RunResult result = run_deck("clear", two_grains_run + "clear\n" + two_grains_run + "print \"STEP $(step)\"\n");
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_EQ(error_line(result.output), "") << result.output;
  EXPECT_NE(result.output.find("\nSTEP 10\n"), std::string::npos) << result.output;
}

TEST(Clear, TakesNoArguments)
{
  const RunResult result = run_deck("clear_argument", "clear all\n");
  EXPECT_NE(result.exit_status, 0) << result.output;
  EXPECT_NE(error_line(result.output).find("Illegal clear command"), std::string::npos) << result.output;
}

}  // namespace
