// Overlaps among the grains of fix contact/dynamics and with its walls, at the positions now:
// the warning at a run's start (rigid contacts keep the overlaps grains were created with) and
// outputs 5 and 6, measured when read and at most once a step.
#pragma once

#include <vector>

#include "cd/walls.h"
#include "lmptype.h"
#include "pointers.h"

namespace LAMMPS_NS {
class NeighList;

class OverlapGauge : protected Pointers {
 public:
  OverlapGauge(LAMMPS* lmp, const std::vector<cd::Wall>& walls) : Pointers(lmp), walls_(walls) {}

  // What the gauge looks at: the fix's neighbour list and group, the box now.
  void look_at(const NeighList* list, int groupbit)
  {
    list_ = list;
    groupbit_ = groupbit;
  }
  // At a run's start: a warning if contacts overlap by more than a hundredth of a diameter;
  // the outputs are measured anew.
  void warn_initial(const cd::PeriodicBox& box, double mean_diameter);
  // Outputs 5 and 6 (in mean diameters, over all ranks; the mean over `solved_contacts`), measured
  // unless they were this step. Called on every rank.
  void measure_if_stale(const cd::PeriodicBox& box, double mean_diameter, double solved_contacts);
  double deepest() const { return deepest_; }
  double mean() const { return mean_; }

 private:
  template <class Visit>
  void for_each_overlap(const cd::PeriodicBox& box, Visit&& visit) const;

  const std::vector<cd::Wall>& walls_;
  const NeighList* list_ = nullptr;
  int groupbit_ = 0;
  double deepest_ = 0.0, mean_ = 0.0;
  bigint measured_at_ = -1;  // the step they were measured at; -1: not yet this run
};

}  // namespace LAMMPS_NS
