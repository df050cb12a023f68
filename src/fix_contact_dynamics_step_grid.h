// The step that follows the flow for fix contact/dynamics (dt_max; cd::StepGrid): at the start
// of a run the level is taken from the grains' speeds unless a previous run or a restart left
// one, then revised each time an alignment period ends; the time step is set as fix dt/reset
// sets it. And LAMMPS's clock, which a varying step keeps by time, not by step count.
#pragma once

#include <functional>
#include <string>
#include <utility>

#include "cd/time_step.h"
#include "pointers.h"

namespace LAMMPS_NS {

// LAMMPS's time now (s), and setting it.
double lammps_time(const Update& update);
void set_lammps_time(Update& update, double time);

class StepGridControl : protected Pointers {
 public:
  // `grid`: dt_max and the alignment period; its travel is set at setup from the skin. `stop`
  // ends the run with the line it is given when a grain is too fast for the smallest step
  // (it does not return: the host writes a restart first, then stops).
  using Stop = std::function<void(const std::string& why)>;
  StepGridControl(LAMMPS* lmp, const cd::StepGrid& grid, double travel_fraction, Stop stop)
      : Pointers(lmp), grid_(grid), travel_fraction_(travel_fraction), stop_(std::move(stop))
  {
  }
  bool on() const { return grid_.dt_max > 0.0; }
  const cd::StepGrid& grid() const { return grid_; }

  // At a run's setup: the grid's travel, the level (unless known), the step.
  void setup(int groupbit);
  // After every step: at the end of a period, the level the fastest grain needs now.
  void end_of_step(int groupbit);

  // What a restart keeps: the clock, if known, on this grid.
  const cd::StepClock& clock() const { return clock_; }
  void restore(const cd::StepClock& clock) { clock_ = clock; }

 private:
  int fastest_grain_level(int groupbit);
  void set_timestep(double dt);

  cd::StepGrid grid_;
  double travel_fraction_;  // of the neighbour skin
  Stop stop_;
  cd::StepClock clock_;
};

}  // namespace LAMMPS_NS
