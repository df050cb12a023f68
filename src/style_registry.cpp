#include "style_registry.h"

#include "fix_contact_dynamics.h"
#include "lammps.h"
#include "modify.h"

namespace LAMMPS_NS {
namespace {

template <typename T>
Fix* create_fix(LAMMPS* lmp, int narg, char** arg)
{
  return new T(lmp, narg, arg);
}

const FixStyleEntry fix_styles[] = {
    {"contact/dynamics", "rigid-disk non-smooth Contact Dynamics (Moreau-Jean, Gauss-Seidel)",
     &create_fix<FixContactDynamics>},
};

}  // namespace

const FixStyleEntry* project_fix_styles(int& count)
{
  count = sizeof(fix_styles) / sizeof(fix_styles[0]);
  return fix_styles;
}

void register_project_styles(LAMMPS* lmp)
{
  for (const FixStyleEntry& style : fix_styles) (*lmp->modify->fix_map)[style.name] = style.create;
}

}  // namespace LAMMPS_NS
