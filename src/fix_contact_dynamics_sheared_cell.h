// Sheared and tilted cells of fix contact/dynamics (doc/plane_shear.md): which box changes the fix
// follows, the box as a step meets it, and the images across the sides of a deforming box
// (fix deform ... remap v), which move with the box and are met at the grains' instant x_m.
#pragma once

#include <vector>

#include "cd/step.h"
#include "cd/walls.h"
#include "pointers.h"

namespace LAMMPS_NS {
class Fix;

class ShearedCell : protected Pointers {
 public:
  explicit ShearedCell(LAMMPS* lmp) : Pointers(lmp) {}

  // At init: refuses box changes the step cannot follow (one error line naming the fix) and
  // notes whether the box deforms. `fix` is the contact fix, `adaptive_step` its dt_max.
  void check_box_changes(const Fix& fix, bool adaptive_step);
  bool deforms() const { return deforms_; }

  // The box now, as LAMMPS holds it.
  cd::PeriodicBox box_now() const;
  // Each step: the box at the step's predicted configuration, where its images are met.
  void begin_step(const cd::StepParameters& step) { step_box_ = box_now().advanced(step.lead()); }
  const cd::PeriodicBox& step_box() const { return step_box_; }

  // Before LAMMPS wraps the grains that crossed a periodic side (pre_exchange): each goes where
  // the step meets the image it becomes.
  void lead_wrapped_grains(const cd::StepParameters& step);

  // Every ghost's edge vectors from its owner, by forward communication (the fix sends them):
  // cleared for `atoms` owned and ghost atoms, then packed and unpacked, two values an atom.
  void clear_image_shifts(int atoms) { image_shift_.assign(atoms, cd::PeriodicBox::Shift{}); }
  int pack_image_shifts(int n, const int* list, double* buf, int pbc_flag, const int* pbc) const;
  void unpack_image_shifts(int n, int first, const double* buf);

  // Velocity of an atom's image relative to its owner (m/s): zero unless the box deforms.
  void image_velocity(int atom_index, double& vx, double& vy) const;

 private:
  bool deforms_ = false;
  cd::PeriodicBox step_box_;
  std::vector<cd::PeriodicBox::Shift> image_shift_;  // per owned and ghost atom
};

}  // namespace LAMMPS_NS
