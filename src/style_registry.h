// The project's LAMMPS styles, registered by name: one list for the executable and the plugin.
#pragma once

namespace LAMMPS_NS {
class LAMMPS;
class Fix;

struct FixStyleEntry {
  const char* name;
  const char* info;
  Fix* (*create)(LAMMPS*, int, char**);
};

// Every fix style of this project.
const FixStyleEntry* project_fix_styles(int& count);

// Adds the project's styles to a LAMMPS instance (its Modify style maps).
void register_project_styles(LAMMPS* lmp);
}  // namespace LAMMPS_NS
