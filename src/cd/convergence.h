// Convergence measures of the Gauss–Seidel sweep, kept apart from the sweep: they are physics.
#pragma once

#include <algorithm>
#include <cmath>

#include "cd/coulomb_local.h"

namespace cd {

// Both norms compare the local velocity change W·dp made by one sweep with the velocity
// scale W·p carried by the impulses (LMGC90's Quad and Maxm): they are dimensionless and do
// not depend on grain size, mass or time step, so one tolerance serves every scene.
enum class ConvergenceNorm {
  quadratic,  // sqrt(sum |W dp|^2 / sum |W p|^2): an average over contacts
  maximum     // max |W dp| / mean |W p|: the worst contact
};

// Sums over the contacts of one sweep; plain fields so that ranks can reduce them (sums with
// MPI_SUM, max_change with MPI_MAX).
struct SweepChange {
  double sum_change_sq = 0.0;  // sum |W dp|^2
  double sum_scale_sq = 0.0;   // sum |W p|^2
  double max_change = 0.0;     // max |W dp|
  double sum_scale = 0.0;      // sum |W p|
  double contacts = 0.0;       // number of contacts visited

  // Inline: called once per contact update in the sweep.
  void add(Local2 velocity_change, Local2 velocity_scale)
  {
    const double change_sq = velocity_change.n * velocity_change.n + velocity_change.t * velocity_change.t;
    const double scale_sq = velocity_scale.n * velocity_scale.n + velocity_scale.t * velocity_scale.t;
    sum_change_sq += change_sq;
    sum_scale_sq += scale_sq;
    max_change = std::max(max_change, std::sqrt(change_sq));
    sum_scale += std::sqrt(scale_sq);
    contacts += 1.0;
  }

  // Adds another set of contacts' sums (another rank's, another block's).
  void merge(const SweepChange& other)
  {
    sum_change_sq += other.sum_change_sq;
    sum_scale_sq += other.sum_scale_sq;
    max_change = std::max(max_change, other.max_change);
    sum_scale += other.sum_scale;
    contacts += other.contacts;
  }

  // The chosen norm; 0 when nothing changed, infinite when impulses changed but all vanished.
  double residual(ConvergenceNorm norm) const;
};

}  // namespace cd
