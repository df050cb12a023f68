// The time step that follows the flow. Steps are dt_max / 2^level, and the level changes only
// when the time is a multiple of an alignment period (a whole number of steps at dt_max): every
// multiple of that period is then reached exactly whatever the levels taken, so signals sampled
// on it stay uniform in time. At each such time the level is the smallest whose step keeps the
// fastest grain's travel per step within a bound (a fraction of the neighbour skin): slow scenes
// take dt_max, fast ones smaller steps, and no grain outruns the neighbour list.
#pragma once

namespace cd {

struct StepGrid {
  double dt_max = 0.0;      // s
  int steps_per_align = 1;  // alignment period in steps of dt_max
  double travel = 0.0;      // m: largest displacement of a grain in one step
  int max_level = 12;       // smallest step dt_max / 2^max_level

  double step(int level) const;                 // s
  long long steps_per_period(int level) const;  // steps in one alignment period at that step
  // Smallest level whose step keeps max_speed (m/s) * step <= travel; -1 if none up to max_level.
  int level_for(double max_speed) const;
  double period() const;                 // s: the alignment period
  bool on_alignment(double time) const;  // time (s) a whole number of periods, to 1e-9 of one
};

// Where a run stands on the grid: its level and the steps taken into the current alignment
// period; the level may change only when a period ends.
struct StepClock {
  int level = 0;
  long long steps_into_period = 0;
  bool known = false;  // set by a run's start or read from a restart

  // Starts at a whole period, at `at_level`.
  void start(int at_level)
  {
    level = at_level;
    steps_into_period = 0;
    known = true;
  }
  // Counts one step; true when it ended an alignment period (the level may change now).
  bool advance(const StepGrid& grid)
  {
    if (++steps_into_period < grid.steps_per_period(level)) return false;
    steps_into_period = 0;
    return true;
  }
};

}  // namespace cd
