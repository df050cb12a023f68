#include "fix_contact_dynamics_sheared_cell.h"

#include "atom.h"
#include "cd/kinematics.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_deform.h"
#include "modify.h"
#include "utils.h"

using namespace LAMMPS_NS;

// A deforming box is followed when its images move at its rates (remap v, LAMMPS's Lees-Edwards
// cell) and every atom's velocity is remapped as it crosses a side (group all). Other fixes that
// change the box's size or shape (press/berendsen, nph, box/relax; not fix balance, which moves
// only the subdomains) rescale the grains through their contacts. remap x moves
// grains affinely through their contacts at the end of the step; remap none leaves a grain that
// crosses the sheared side at its old velocity. fix deform sets the box by step count, not time.
void ShearedCell::check_box_changes(const Fix& fix, bool adaptive_step)
{
  deforms_ = false;
  for (int f = 0; f < modify->nfix; f++) {
    const Fix* other = modify->fix[f];
    const bool deform = utils::strmatch(other->style, "^deform");
    if (other != &fix && (other->box_change & (Fix::BOX_CHANGE_SIZE | Fix::BOX_CHANGE_SHAPE)) && !deform)
      error->all(FLERR,
                 "Fix contact/dynamics: fix {} ({}) changes the box and moves the grains with it: only fix deform "
                 "with remap v is followed",
                 other->id, other->style);
    if (!deform) continue;
    const auto* deformer = static_cast<const FixDeform*>(other);
    if (deformer->remapflag != Domain::V_REMAP)
      error->all(FLERR,
                 "Fix contact/dynamics: fix {} (deform) must use remap v: remap x moves grains through their "
                 "contacts, remap none leaves a grain crossing a moving side at its old velocity",
                 deformer->id);
    if (deformer->igroup != 0)
      error->all(FLERR, "Fix contact/dynamics: fix {} (deform) must act on group all to remap every velocity",
                 deformer->id);
    if (adaptive_step)
      error->all(FLERR, "Fix contact/dynamics: fix {} (deform) counts steps, not time: it cannot follow dt_max",
                 deformer->id);
    deforms_ = true;
  }
}

cd::PeriodicBox ShearedCell::box_now() const
{
  const double* rate = domain->h_rate;  // Voigt: xx, yy, zz, yz, xz, xy
  return {domain->xperiodic != 0,
          domain->yperiodic != 0,
          domain->xprd,
          domain->yprd,
          domain->triclinic ? domain->xy : 0.0,
          rate[0],
          rate[1],
          rate[5]};
}

// LAMMPS is about to wrap the grains that crossed a periodic side (Domain::pbc), by the box of
// the start of the step, adding the velocity of the image they become (remap v). The step meets
// that image at the predicted configuration, where the box has moved on by (1 - theta) dt at its
// rates (as every ghost is met): the grain goes there too.
void ShearedCell::lead_wrapped_grains(const cd::StepParameters& step)
{
  if (!deforms_) return;
  const cd::PeriodicBox box = box_now();
  double** x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    const cd::PeriodicBox::Shift wrapped = box.wrapping(x[i][0] - domain->boxlo[0], x[i][1] - domain->boxlo[1]);
    if (wrapped.x == 0 && wrapped.y == 0) continue;
    double vx = 0.0, vy = 0.0;
    box.image_velocity(wrapped, vx, vy);
    const cd::Displacement lead = cd::image_lead(vx, vy, step);
    x[i][0] += lead.dx;
    x[i][1] += lead.dy;
  }
}

// The sum of the periodic sides a ghost's copies crossed, as LAMMPS shifts its position.
int ShearedCell::pack_image_shifts(int n, const int* list, double* buf, int pbc_flag, const int* pbc) const
{
  const int across_x = pbc_flag ? pbc[0] : 0, across_y = pbc_flag ? pbc[1] : 0;
  int m = 0;
  for (int k = 0; k < n; k++) {
    buf[m++] = image_shift_[list[k]].x + across_x;
    buf[m++] = image_shift_[list[k]].y + across_y;
  }
  return m;
}

void ShearedCell::unpack_image_shifts(int n, int first, const double* buf)
{
  for (int g = first, m = 0; g < first + n; g++, m += 2)
    image_shift_[g] = {static_cast<int>(buf[m]), static_cast<int>(buf[m + 1])};
}

void ShearedCell::image_velocity(int atom_index, double& vx, double& vy) const
{
  if (!deforms_ || atom_index < atom->nlocal) {
    vx = vy = 0.0;
    return;
  }
  step_box_.image_velocity(image_shift_[atom_index], vx, vy);
}
