#include "fix_contact_dynamics_overlaps.h"

#include <algorithm>
#include <cmath>

#include "comm.h"
#include "error.h"
#include "fix_contact_dynamics_listed_pairs.h"
#include "update.h"

using namespace LAMMPS_NS;

namespace {
// Overlaps deeper than this, in mean diameters, at the start of a run are reported.
constexpr double initial_overlap_warning = 0.01;
}  // namespace

template <class Visit>
void OverlapGauge::visit_if_overlapping(int i, int j, Visit&& visit) const
{
  const double* xi = atom->x[i];
  const double* xj = atom->x[j];
  const double dx = xi[0] - xj[0], dy = xi[1] - xj[1];
  const double touching = atom->radius[i] + atom->radius[j];
  const double distance_sq = dx * dx + dy * dy;
  if (distance_sq < touching * touching) visit(touching - std::sqrt(distance_sq));
}

template <class Visit>
void OverlapGauge::visit_if_on_wall(int i, const cd::Wall& wall, const cd::PeriodicBox& box, Visit&& visit) const
{
  const double* xi = atom->x[i];
  if (const auto touch = cd::wall_contact(wall, 0, {xi[0], xi[1], atom->radius[i]}, 0.0, box))
    if (touch->geometry.gap < 0.0) visit(-touch->geometry.gap);
}

template <class Visit>
void OverlapGauge::visit_if_on_region_wall(int i, int wall, Visit&& visit) const
{
  const double* xi = atom->x[i];
  for (const RegionWalls::Touch& touch : region_walls_.touches(wall, 0, {xi[0], xi[1], atom->radius[i]}, 0.0, 0.0))
    if (touch.geometry.gap < 0.0) visit(-touch.geometry.gap);
}

// The depth (m, > 0) of every overlapping listed pair with a grain and of every grain overlapping
// a wall. Most listed pairs are apart: the squared distance tells them without a square root.
template <class Visit>
void OverlapGauge::for_each_overlap(const cd::PeriodicBox& box, Visit&& visit) const
{
  const int* mask = atom->mask;
  for_each_listed_pair(*list_, *atom, [&](int i, int j) {
    if ((mask[i] & groupbit_) || (mask[j] & groupbit_)) visit_if_overlapping(i, j, visit);
  });
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit_)) continue;
    for (const cd::Wall& wall : walls_) visit_if_on_wall(i, wall, box, visit);
    for (int r = 0; r < region_walls_.count(); r++) visit_if_on_region_wall(i, r, visit);
  }
}

// The same over the pairs and walls the step looked at.
template <class Visit>
void OverlapGauge::for_each_watched_overlap(const cd::PeriodicBox& box, Visit&& visit) const
{
  for (const AtomPair& pair : watched_pairs_) visit_if_overlapping(pair.i, pair.j, visit);
  for (const AtomPair& pair : watched_walls_) visit_if_on_wall(pair.i, walls_[pair.j], box, visit);
  for (const AtomPair& pair : watched_region_walls_) visit_if_on_region_wall(pair.i, pair.j, visit);
}

void OverlapGauge::begin_look()
{
  watched_pairs_.clear();
  watched_walls_.clear();
  watched_region_walls_.clear();
  looked_at_ = update->ntimestep;
}

// Rigid contacts never push overlapping grains apart: grains created overlapping (random
// placement, a lattice that does not fit the periodic cell) stay so. Say it at the start.
void OverlapGauge::warn_initial(const cd::PeriodicBox& box, double mean_diameter)
{
  measured_at_ = -1;
  looked_at_ = -1;  // atoms may have moved since the last run's look
  const double threshold = initial_overlap_warning * mean_diameter;
  double local[2] = {0.0, 0.0};  // count, deepest
  for_each_overlap(box, [&](double depth) {
    if (depth <= threshold) return;
    local[0] += 1.0;
    local[1] = std::max(local[1], depth);
  });
  double global[2];
  MPI_Allreduce(&local[0], &global[0], 1, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(&local[1], &global[1], 1, MPI_DOUBLE, MPI_MAX, world);
  if (global[0] > 0.0 && comm->me == 0)
    error->warning(FLERR,
                   "Fix contact/dynamics: {} contacts overlap by up to {:.3g} mean diameters "
                   "at the start of the run; rigid contacts keep such overlaps, create the grains "
                   "apart",
                   static_cast<bigint>(global[0]), global[1] / mean_diameter);
}

// From the positions when they are read, after every fix has moved its atoms (the corrector,
// fix move, ...): what a user measures at the end of the step. The ghosts are brought to their
// owners' positions first.
void OverlapGauge::measure_if_stale(const cd::PeriodicBox& box, double mean_diameter, double solved_contacts)
{
  if (measured_at_ == update->ntimestep) return;
  comm->forward_comm();
  double local[2] = {0.0, 0.0};  // deepest, sum (m)
  const auto add = [&](double depth) {
    local[0] = std::max(local[0], depth);
    local[1] += depth;
  };
  if (looked_at_ == update->ntimestep) for_each_watched_overlap(box, add);
  else for_each_overlap(box, add);
  double deepest = 0.0, total = 0.0;
  MPI_Allreduce(&local[0], &deepest, 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(&local[1], &total, 1, MPI_DOUBLE, MPI_SUM, world);
  deepest_ = deepest / mean_diameter;
  mean_ = solved_contacts > 0.0 ? total / solved_contacts / mean_diameter : 0.0;
  measured_at_ = update->ntimestep;
}
