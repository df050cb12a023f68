// peer_bench --repeat (bench/peers/repeated_runs.h): a short solve's time is the median of its
// runs, and the runs stop at the count or once their times add up to the budget.
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "repeated_runs.h"

namespace {

struct Timed {
  double seconds = 0.0;
  int runs = 0;
  int last = -1;  // which run the outcome came from
};

// A solve whose n-th run takes times[n] seconds.
struct ScriptedSolve {
  std::vector<double> times;
  int calls = 0;
  Timed operator()()
  {
    Timed t;
    t.seconds = times.at(static_cast<std::size_t>(calls));
    t.last = calls++;
    return t;
  }
};

TEST(RepeatedRuns, MedianOfOddAndEvenCounts)
{
  std::vector<double> odd{5.0, 1.0, 3.0};
  EXPECT_EQ(peers::median(odd), 3.0);
  std::vector<double> even{4.0, 1.0, 3.0, 2.0};
  EXPECT_EQ(peers::median(even), 2.5);
  std::vector<double> one{7.0};
  EXPECT_EQ(peers::median(one), 7.0);
}

// The first run of a fresh process is slow (its memory's first touches); the median is the method's.
TEST(RepeatedRuns, ShortSolveTimedByTheMedianOfItsRuns)
{
  ScriptedSolve solve{{9e-4, 1e-4, 2e-4, 1e-4, 3e-4}};
  const Timed t = peers::repeated<Timed>(std::ref(solve), 5, 0.05);
  EXPECT_EQ(solve.calls, 5);
  EXPECT_EQ(t.runs, 5);
  EXPECT_EQ(t.last, 4);
  EXPECT_DOUBLE_EQ(t.seconds, 2e-4);
}

// A long solve is not run again past the budget: here the first two runs already spend it.
TEST(RepeatedRuns, StopsOnceTheRunsSpendTheBudget)
{
  ScriptedSolve solve{{0.03, 0.04, 0.01, 0.01, 0.01}};
  const Timed t = peers::repeated<Timed>(std::ref(solve), 5, 0.05);
  EXPECT_EQ(solve.calls, 2);
  EXPECT_EQ(t.runs, 2);
  EXPECT_DOUBLE_EQ(t.seconds, 0.035);
}

TEST(RepeatedRuns, OneRepeatIsOneRun)
{
  ScriptedSolve solve{{0.2, 0.1}};
  const Timed t = peers::repeated<Timed>(std::ref(solve), 1, 0.05);
  EXPECT_EQ(solve.calls, 1);
  EXPECT_DOUBLE_EQ(t.seconds, 0.2);
}

}  // namespace
