// Overlaps among the grains of fix contact/dynamics and with its walls, at the positions now:
// the warning at a run's start (rigid contacts keep the overlaps grains were created with) and
// outputs 5 and 6, measured when read and at most once a step. Within a step they are measured
// over the pairs and walls the step looked at: the look reaches as far as the solved velocities
// move the grains (cd::PairReach), so no other pair can overlap at its end; a read before a run's
// first step goes over every listed pair.
#pragma once

#include <vector>

#include "cd/walls.h"
#include "fix_contact_dynamics_region_walls.h"
#include "lmptype.h"
#include "pointers.h"

namespace LAMMPS_NS {
class NeighList;

class OverlapGauge : protected Pointers {
 public:
  OverlapGauge(LAMMPS* lmp, const std::vector<cd::Wall>& walls, RegionWalls& region_walls)
      : Pointers(lmp), walls_(walls), region_walls_(region_walls)
  {
  }

  // What the gauge looks at: the fix's neighbour list and group, the box now.
  void look_at(const NeighList* list, int groupbit)
  {
    list_ = list;
    groupbit_ = groupbit;
  }
  // The step's look begins (its first pass): the pairs and walls watched so far are forgotten.
  void begin_look();
  void watch_pair(int i, int j) { watched_pairs_.push_back({i, j}); }
  void watch_wall(int i, int wall) { watched_walls_.push_back({i, wall}); }
  void watch_region_wall(int i, int wall) { watched_region_walls_.push_back({i, wall}); }
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
  template <class Visit>
  void for_each_watched_overlap(const cd::PeriodicBox& box, Visit&& visit) const;
  template <class Visit>
  void visit_if_overlapping(int i, int j, Visit&& visit) const;
  template <class Visit>
  void visit_if_on_wall(int i, const cd::Wall& wall, const cd::PeriodicBox& box, Visit&& visit) const;
  template <class Visit>
  void visit_if_on_region_wall(int i, int wall, Visit&& visit) const;

  struct AtomPair {
    int i, j;  // atom indices; for a wall, j is the wall's number
  };

  const std::vector<cd::Wall>& walls_;
  RegionWalls& region_walls_;  // where they stand when the gauge reads them: at the step's end
  const NeighList* list_ = nullptr;
  int groupbit_ = 0;
  double deepest_ = 0.0, mean_ = 0.0;
  bigint measured_at_ = -1;  // the step they were measured at; -1: not yet this run
  std::vector<AtomPair> watched_pairs_, watched_walls_, watched_region_walls_;
  bigint looked_at_ = -1;  // the step whose look filled them
};

}  // namespace LAMMPS_NS
