#include "fix_contact_dynamics_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "group.h"
#include "lammps.h"
#include "modify.h"
#include "pair.h"
#include "utils.h"

using namespace LAMMPS_NS;

namespace {
// Relative spread below which a mass/radius^k ratio counts as uniform over the group.
constexpr double uniform_ratio_tolerance = 1.0e-6;

// The first fix pour, or none.
const Fix* pour_fix(LAMMPS* lmp)
{
  const Modify& modify = *lmp->modify;
  for (int f = 0; f < modify.nfix; f++)
    if (utils::strmatch(modify.fix[f]->style, "^pour")) return modify.fix[f];
  return nullptr;
}
}  // namespace

// fix pour in this LAMMPS (29 Sep 2021) resizes the atom map after an insertion step only when
// the last grain it tried fitted: a step that places fewer grains than it asked for (a crowded
// insertion region) leaves an array map too short for the new atom IDs, and Atom::map_set
// writes past its end (a segmentation fault). A hash map grows by itself; `map yes` is an array
// below a million atom IDs.
void fix_checks::insertion_map(LAMMPS* lmp)
{
  const Fix* pour = pour_fix(lmp);
  if (pour && lmp->atom->map_style != Atom::MAP_HASH)
    lmp->error->all(FLERR,
                    "Fix contact/dynamics: fix {} (pour) crashes this LAMMPS with an array atom map (map array "
                    "or yes) when an insertion falls short; use atom_modify map hash",
                    pour->id);
}

// LAMMPS's fix pour and fix move refuse a step that changes during a run ("Cannot change
// timestep with fix pour", "Resetting timestep size is not allowed with fix move"): said before
// the run, naming the fix and what to do.
void fix_checks::fixed_step_fixes(LAMMPS* lmp)
{
  const Modify& modify = *lmp->modify;
  for (int f = 0; f < modify.nfix; f++) {
    const Fix& other = *modify.fix[f];
    const char* remedy = utils::strmatch(other.style, "^pour")   ? "pour at a fixed step, then continue with dt_max"
                         : utils::strmatch(other.style, "^move") ? "give the step with timestep instead of dt_max"
                                                                 : nullptr;
    if (remedy)
      lmp->error->all(FLERR,
                      "Fix contact/dynamics: fix {} ({}) cannot follow dt_max: it stops the run when the step "
                      "changes; {}",
                      other.id, other.style, remedy);
  }
}

void fix_checks::integrators(LAMMPS* lmp, const Fix& fix)
{
  const Atom& atom = *lmp->atom;
  Modify& modify = *lmp->modify;
  for (int f = 0; f < modify.nfix; f++) {
    const Fix* other = modify.fix[f];
    if (other == &fix || !other->time_integrate) continue;
    int shared_local = (other->igroup == fix.igroup || other->igroup == 0 || fix.igroup == 0) ? 1 : 0;
    for (int i = 0; i < atom.nlocal && !shared_local; i++)
      if ((atom.mask[i] & fix.groupbit) && (atom.mask[i] & other->groupbit)) shared_local = 1;
    int shared = 0;
    MPI_Allreduce(&shared_local, &shared, 1, MPI_INT, MPI_MAX, lmp->world);
    if (shared)
      lmp->error->all(FLERR, "Fix contact/dynamics: fix {} ({}) also integrates atoms of group {}", other->id,
                      other->style, lmp->group->names[fix.igroup]);
  }
}

// A pair style's forces between two grains of the group would act on top of the rigid
// contacts (springs added to contacts that never overlap): refused (the fix asks this unless
// pair_forces yes says they are wanted, e.g. cohesion). Pair::init() has set cutsq for every
// type pair by now; a type pair with no interaction (pair_style none, hybrid none) has cutsq 0,
// pair_style zero exerts no force.
void fix_checks::pair_style(LAMMPS* lmp, const Fix& fix)
{
  const Pair* pair = lmp->force->pair;
  if (!pair || !pair->cutsq || utils::strmatch(lmp->force->pair_style, "^zero")) return;
  const Atom& atom = *lmp->atom;
  const int ntypes = atom.ntypes;
  std::vector<int> present_local(ntypes + 1, fix.igroup == 0 ? 1 : 0), present(ntypes + 1, 0);
  for (int i = 0; i < atom.nlocal; i++)
    if (atom.mask[i] & fix.groupbit) present_local[atom.type[i]] = 1;
  MPI_Allreduce(present_local.data(), present.data(), ntypes + 1, MPI_INT, MPI_MAX, lmp->world);
  for (int itype = 1; itype <= ntypes; itype++)
    for (int jtype = itype; jtype <= ntypes; jtype++)
      if (present[itype] && present[jtype] && pair->cutsq[itype][jtype] > 0.0)
        lmp->error->all(FLERR,
                        "Fix contact/dynamics: pair style {} also acts on atoms of group {} (types {} and {}); "
                        "remove it, or add pair_forces yes to keep its forces",
                        lmp->force->pair_style, lmp->group->names[fix.igroup], itype, jtype);
}

// Disks need m = pi r^2 rho. Sphere masses (4/3 pi r^3 rho, as fix pour and set density give)
// show in a polydisperse group as a uniform mass/r^3 with a non-uniform mass/r^2; in a group of
// one radius both are uniform, whichever rule made the masses.
std::optional<double> fix_checks::disk_masses(LAMMPS* lmp, const Fix& fix)
{
  const Atom& atom = *lmp->atom;
  double local[4];  // max m/r^2, max -m/r^2, max m/r^3, max -m/r^3
  for (double& value : local) value = -HUGE_VAL;
  for (int i = 0; i < atom.nlocal; i++) {
    if (!(atom.mask[i] & fix.groupbit)) continue;
    const double r = atom.radius[i];
    if (r <= 0.0 || atom.rmass[i] <= 0.0)
      lmp->error->one(FLERR, "Fix contact/dynamics: atom {} has radius {} and mass {}; both must be > 0", atom.tag[i],
                      r, atom.rmass[i]);
    const double per_area = atom.rmass[i] / (r * r);
    const double per_volume = per_area / r;
    local[0] = std::max(local[0], per_area);
    local[1] = std::max(local[1], -per_area);
    local[2] = std::max(local[2], per_volume);
    local[3] = std::max(local[3], -per_volume);
  }
  double global[4];
  MPI_Allreduce(local, global, 4, MPI_DOUBLE, MPI_MAX, lmp->world);
  if (global[0] == -HUGE_VAL) return std::nullopt;  // no grain
  const bool area_uniform = global[0] <= -global[1] * (1.0 + uniform_ratio_tolerance);
  const bool volume_uniform = global[2] <= -global[3] * (1.0 + uniform_ratio_tolerance);
  if (!area_uniform && volume_uniform)
    lmp->error->all(FLERR,
                    "Fix contact/dynamics: group {} has sphere masses (4/3 pi r^3 rho); use set "
                    "density/disc or the density keyword",
                    lmp->group->names[fix.igroup]);
  if (area_uniform && volume_uniform) return global[0] / M_PI;
  return std::nullopt;
}

// An RCB tiling may split either axis. A triclinic box splits in reduced coordinates: a slice
// along x is bounded by lines along the tilted edge (xy, ly), a slice along y by lines along x.
double fix_checks::narrowest_split_subdomain(LAMMPS* lmp)
{
  const Domain& domain = *lmp->domain;
  const Comm& comm = *lmp->comm;
  double width[2];
  if (domain.triclinic) {
    width[0] = (domain.subhi_lamda[0] - domain.sublo_lamda[0]) * domain.xprd * domain.yprd /
               std::hypot(domain.yprd, domain.xy);
    width[1] = (domain.subhi_lamda[1] - domain.sublo_lamda[1]) * domain.yprd;
  } else {
    for (int axis = 0; axis < 2; axis++) width[axis] = domain.subhi[axis] - domain.sublo[axis];
  }
  double local = std::numeric_limits<double>::max();
  for (int axis = 0; axis < 2; axis++)
    if (comm.layout == Comm::LAYOUT_TILED || comm.procgrid[axis] > 1) local = std::min(local, width[axis]);
  double global = local;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MIN, lmp->world);
  return global;
}
