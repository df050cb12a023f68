// The checks of the LAMMPS set-up that fix contact/dynamics runs in. Each stops the run with one
// error line naming what to change; `fix` is the contact fix (its group and ID).
#pragma once

#include <optional>

namespace LAMMPS_NS {
class Fix;
class LAMMPS;

namespace fix_checks {

// fix pour with an array atom map (it writes past the map's end after a short insertion).
void insertion_map(LAMMPS* lmp);
// fix pour or fix move beside the step that follows the flow (dt_max): they stop the run at the
// first change of the step.
void fixed_step_fixes(LAMMPS* lmp);
// Another fix integrating atoms of the group.
void integrators(LAMMPS* lmp, const Fix& fix);
// A pair style acting between grains of the group (springs on top of rigid contacts).
void pair_style(LAMMPS* lmp, const Fix& fix);
// Radius and mass > 0 for every grain, and no sphere masses (m/r^3 uniform, m/r^2 not). Masses of
// one radius cannot tell disks from spheres: then the areal density m / (pi r^2) they imply.
std::optional<double> disk_masses(LAMMPS* lmp, const Fix& fix);
// Width of the narrowest subdomain, over all ranks, along the axes split between ranks.
double narrowest_split_subdomain(LAMMPS* lmp);

}  // namespace fix_checks
}  // namespace LAMMPS_NS
