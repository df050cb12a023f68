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
  double face_changes = 0.0;   // contacts whose law face changed (counted under over_relaxation only)

  // One contact's W dp and W p, for the quadratic norm only: no square root, which is what
  // its sweeps accumulate (called once per contact update).
  void add_squares(Local2 velocity_change, Local2 velocity_scale)
  {
    sum_change_sq += velocity_change.n * velocity_change.n + velocity_change.t * velocity_change.t;
    sum_scale_sq += velocity_scale.n * velocity_scale.n + velocity_scale.t * velocity_scale.t;
    contacts += 1.0;
  }

  // One contact's W dp and W p, for either norm.
  void add(Local2 velocity_change, Local2 velocity_scale)
  {
    add_squares(velocity_change, velocity_scale);
    max_change =
        std::max(max_change, std::sqrt(velocity_change.n * velocity_change.n + velocity_change.t * velocity_change.t));
    sum_scale += std::sqrt(velocity_scale.n * velocity_scale.n + velocity_scale.t * velocity_scale.t);
  }

  // Adds another set of contacts' sums (another rank's, another block's).
  void merge(const SweepChange& other)
  {
    sum_change_sq += other.sum_change_sq;
    sum_scale_sq += other.sum_scale_sq;
    max_change = std::max(max_change, other.max_change);
    sum_scale += other.sum_scale;
    contacts += other.contacts;
    face_changes += other.face_changes;
  }

  // The chosen norm; 0 when nothing changed, infinite when impulses changed but all vanished.
  double residual(ConvergenceNorm norm) const;

  // The square of the change |W dp| below which a contact of this sweep counts as quiet: were
  // every contact that quiet, the norm would be at most fraction * tolerance.
  double quiet_change_sq(ConvergenceNorm norm, double tolerance, double fraction) const;
};

}  // namespace cd
