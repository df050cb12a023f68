// The contact part of the pressure tensor of fix contact/dynamics, (1 / (A dt))
// cd::branch_impulse_sums, as LAMMPS's pair virial: into the fix's virial (energy units, summed
// over the ranks by compute pressure) on the steps that ask for it, and outputs 13-16 (xx, yy, xy,
// yx; N/m in 2D SI) summed over the ranks when read, at most once a step.
#pragma once

#include "cd/detection.h"
#include "pointers.h"

namespace LAMMPS_NS {

class ContactStressGauge : protected Pointers {
 public:
  explicit ContactStressGauge(LAMMPS* lmp) : Pointers(lmp) {}
  // After a step's solve, with the step's contacts (kept until the next step); `virial`, if
  // given, takes this rank's share.
  void after_step(const cd::StepContacts& contacts, double* virial);
  // An output (0 xx, 1 yy, 2 xy, 3 yx) of the last step. Called on every rank.
  double component(int k);

 private:
  const cd::StepContacts* contacts_ = nullptr;
  double area_dt_ = 0.0;     // the box's area times the step of the last step
  double pressure_[4] = {};  // xx, yy, xy, yx over all ranks
  bool measured_ = true;     // pressure_ holds the last step's
};

}  // namespace LAMMPS_NS
