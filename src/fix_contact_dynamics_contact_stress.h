// The contact part of the pressure tensor of fix contact/dynamics, (1 / (A dt))
// cd::branch_impulse_sums, as LAMMPS's pair virial: into the fix's virial (energy units, summed
// over the ranks by compute pressure) and atom by atom (cd::for_each_branch_impulse_share, into the
// fix's vatom for compute stress/atom) on the steps that ask for them, and outputs 13-16 (xx, yy,
// xy, yx; N/m in 2D SI) summed over the ranks when read, at most once a step.
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
  // This rank's shares of the step's contacts (energy units) into the rows of `vatom` (LAMMPS's
  // xx, yy, zz, xy, xz, yz), the rows of the atoms 0 to `atoms` cleared first: body 1 + i is
  // atom i, owned or a ghost whose share its owner still has to receive.
  void per_atom(const cd::StepContacts& contacts, double** vatom, int atoms);
  // An output (0 xx, 1 yy, 2 xy, 3 yx) of the last step. Called on every rank.
  double component(int k);

 private:
  const cd::StepContacts* contacts_ = nullptr;
  double area_dt_ = 0.0;     // the box's area times the step of the last step
  double pressure_[4] = {};  // xx, yy, xy, yx over all ranks
  bool measured_ = true;     // pressure_ holds the last step's
};

}  // namespace LAMMPS_NS
