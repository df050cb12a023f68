// The grid of the step that follows the flow (cd::StepGrid): levels against the travel bound.
#include <gtest/gtest.h>

#include "cd/time_step.h"

namespace {

const cd::StepGrid grid{1e-4, 10, 3e-4, 12};  // dt_max 1e-4 s, align 1 ms, travel 0.3 mm

TEST(StepGrid, LevelIsTheLargestStepWithinTheTravelBound)
{
  EXPECT_EQ(grid.level_for(0.0), 0);
  EXPECT_EQ(grid.level_for(2.99), 0);  // 2.99 m/s x 1e-4 s < 0.3 mm
  EXPECT_EQ(grid.level_for(3.01), 1);
  EXPECT_EQ(grid.level_for(5.99), 1);
  EXPECT_EQ(grid.level_for(6.01), 2);
  EXPECT_EQ(grid.level_for(2.99 * 4096), 12);
  EXPECT_EQ(grid.level_for(3.0 * 4096 * 1.01), -1) << "no step on the grid is small enough";
}

TEST(StepGrid, EveryLevelFillsTheAlignmentPeriodExactly)
{
  for (int level = 0; level <= grid.max_level; level++) {
    EXPECT_EQ(grid.steps_per_period(level), 10LL << level);
    EXPECT_DOUBLE_EQ(grid.step(level) * static_cast<double>(grid.steps_per_period(level)), 1e-3);
  }
}

TEST(StepGrid, AlignmentTimesAreWholePeriods)
{
  EXPECT_DOUBLE_EQ(grid.period(), 1e-3);
  EXPECT_TRUE(grid.on_alignment(0.0));
  EXPECT_TRUE(grid.on_alignment(4.404));  // 4404 periods, not exactly representable
  EXPECT_TRUE(grid.on_alignment(123.0));
  EXPECT_FALSE(grid.on_alignment(4.4045));  // half a period: a restart at level 1
  EXPECT_FALSE(grid.on_alignment(5e-5));
}

// The clock lets the level change only at the ends of alignment periods: a period at level L
// is 10 x 2^L steps, whatever level the one before had.
TEST(StepClock, APeriodEndsAfterItsLevelsStepsOnly)
{
  cd::StepClock clock;
  EXPECT_FALSE(clock.known);
  clock.start(1);
  EXPECT_TRUE(clock.known);
  for (int step = 1; step < 20; step++) EXPECT_FALSE(clock.advance(grid)) << "step " << step;
  EXPECT_TRUE(clock.advance(grid)) << "a period at level 1 is 20 steps";
  EXPECT_EQ(clock.steps_into_period, 0);
  clock.level = 3;
  for (int step = 1; step < 80; step++) EXPECT_FALSE(clock.advance(grid)) << "step " << step;
  EXPECT_TRUE(clock.advance(grid)) << "a period at level 3 is 80 steps";
}

TEST(StepClock, ARestartedClockFinishesThePeriodItWasIn)
{
  cd::StepClock clock{2, 37, true};  // as a restart written 37 steps into a level-2 period left it
  for (int step = 38; step < 40; step++) EXPECT_FALSE(clock.advance(grid)) << "step " << step;
  EXPECT_TRUE(clock.advance(grid));
}

}  // namespace
