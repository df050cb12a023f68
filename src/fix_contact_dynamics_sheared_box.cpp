// Sheared and tilted cells (doc/plane_shear.md): which box changes the fix follows, and the
// images across the sides of a deforming box (fix deform ... remap v), met at the step's
// predicted configuration.
#include <cmath>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_contact_dynamics.h"
#include "fix_deform.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

using namespace LAMMPS_NS;

// A deforming box is followed when its images move at its rates (remap v, LAMMPS's Lees-Edwards
// cell) and every atom's velocity is remapped as it crosses a side (group all). Other fixes that
// change the box's size or shape (press/berendsen, nph, box/relax; not fix balance, which moves
// only the subdomains) rescale the grains through their contacts. remap x moves
// grains affinely through their contacts at the end of the step; remap none leaves a grain that
// crosses the sheared side at its old velocity. fix deform sets the box by step count, not time.
void FixContactDynamics::check_deforming_box()
{
  domain_deforms = false;
  for (int f = 0; f < modify->nfix; f++) {
    const Fix* other = modify->fix[f];
    if (other != this && (other->box_change & (Fix::BOX_CHANGE_SIZE | Fix::BOX_CHANGE_SHAPE)) &&
        !utils::strmatch(other->style, "^deform"))
      error->all(FLERR,
                 "Fix contact/dynamics: fix {} ({}) changes the box and moves the grains with it: only fix deform "
                 "with remap v is followed",
                 other->id, other->style);
    if (!utils::strmatch(modify->fix[f]->style, "^deform")) continue;
    const auto* deform = static_cast<FixDeform*>(modify->fix[f]);
    if (deform->remapflag != Domain::V_REMAP)
      error->all(FLERR,
                 "Fix contact/dynamics: fix {} (deform) must use remap v: remap x moves grains through their "
                 "contacts, remap none leaves a grain crossing a moving side at its old velocity",
                 deform->id);
    if (deform->igroup != 0)
      error->all(FLERR, "Fix contact/dynamics: fix {} (deform) must act on group all to remap every velocity",
                 deform->id);
    if (settings.adaptive_step())
      error->all(FLERR, "Fix contact/dynamics: fix {} (deform) counts steps, not time: it cannot follow dt_max",
                 deform->id);
    domain_deforms = true;
  }
}

// LAMMPS is about to wrap the grains that crossed a periodic side (Domain::pbc), by the box of
// the start of the step, adding the velocity of the image they become (remap v). The step meets
// that image at the predicted configuration, where the box has moved on by (1 - theta) dt at its
// rates (as every ghost is met, collect_grain_pairs): the grain goes there too.
void FixContactDynamics::pre_exchange()
{
  if (!domain_deforms) return;
  const double lag = step_parameters().lead();
  const cd::PeriodicBox box = periodic_box();
  double** x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    const cd::PeriodicBox::Shift wrapped = box.wrapping(x[i][0] - domain->boxlo[0], x[i][1] - domain->boxlo[1]);
    if (wrapped.x == 0 && wrapped.y == 0) continue;
    double vx = 0.0, vy = 0.0;
    box.image_velocity(wrapped, vx, vy);
    x[i][0] += lag * vx;
    x[i][1] += lag * vy;
  }
}

// Every ghost's edge vectors from its owner (the sum of the periodic sides its copies crossed,
// as LAMMPS shifts its position), refreshed every step: ghosts change at reneighbouring.
void FixContactDynamics::share_image_shifts()
{
  image_shift.assign(atom->nlocal + atom->nghost, cd::PeriodicBox::Shift{});
  sending_image_shifts = true;
  comm->forward_comm_fix(this, 2);
  sending_image_shifts = false;
}

// Velocity of an atom's image relative to its owner (m/s): zero unless the box deforms.
void FixContactDynamics::image_velocity_of(int atom_index, double& vx, double& vy) const
{
  if (!domain_deforms || atom_index < atom->nlocal) {
    vx = vy = 0.0;
    return;
  }
  step_box.image_velocity(image_shift[atom_index], vx, vy);
}
