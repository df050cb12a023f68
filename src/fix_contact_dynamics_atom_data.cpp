// The fix's data across ranks and runs: the bodies' velocities forwarded to ghosts and the
// ghosts' changes sent back (RankExchange, the per-atom virial's reverse sum), the per-atom arrays
// through LAMMPS's exchanges, and the global and per-atom restart records.
#include "fix_contact_dynamics.h"

#include <cstdio>

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_contact_dynamics_step_grid.h"
#include "update.h"

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   Exchange across ranks (RankExchange): the bodies' velocities to the ghosts, the ghosts'
   changes over a sweep back to their owners.
------------------------------------------------------------------------- */

int FixContactDynamics::pack_forward_comm(int n, int* list, double* buf, int pbc_flag, int* pbc)
{
  if (forward_field == ForwardField::obstacle_travel) return obstacles.pack_travel(n, list, buf);
  if (forward_field == ForwardField::image_shift) return sheared_cell.pack_image_shifts(n, list, buf, pbc_flag, pbc);
  int m = 0;
  for (int k = 0; k < n; k++) {
    const cd::BodyVelocity& velocity = bodies.velocity[body_of_atom[list[k]]];
    buf[m++] = velocity.vx;
    buf[m++] = velocity.vy;
    buf[m++] = velocity.spin;
  }
  return m;
}

void FixContactDynamics::unpack_forward_comm(int n, int first, double* buf)
{
  if (forward_field == ForwardField::obstacle_travel) return obstacles.unpack_travel(n, first, buf);
  if (forward_field == ForwardField::image_shift) return sheared_cell.unpack_image_shifts(n, first, buf);
  int m = 0;
  for (int g = first; g < first + n; g++, m += 3) {
    if (body_of_atom[g] != 1 + g) continue;  // an image: its body is updated elsewhere
    const cd::BodyVelocity velocity{buf[m], buf[m + 1], buf[m + 2]};
    bodies.velocity[1 + g] = velocity;
    ghost_reference[1 + g] = velocity;
  }
}

cd::BodyVelocity FixContactDynamics::velocity_change_of_ghost(int g) const
{
  if (body_of_atom[g] != 1 + g) return {};  // images of owned atoms change their owner directly
  const cd::BodyVelocity& now = bodies.velocity[1 + g];
  const cd::BodyVelocity& before = ghost_reference[1 + g];
  return {now.vx - before.vx, now.vy - before.vy, now.spin - before.spin};
}

int FixContactDynamics::pack_reverse_comm(int n, int first, double* buf)
{
  int m = 0;
  if (reverse_field == ReverseField::virial) {
    for (int g = first; g < first + n; g++)
      for (const int k : peratom_virial_components) buf[m++] = vatom[g][k];
    return m;
  }
  for (int g = first; g < first + n; g++) {
    const cd::BodyVelocity change = velocity_change_of_ghost(g);
    buf[m++] = change.vx;
    buf[m++] = change.vy;
    buf[m++] = change.spin;
  }
  return m;
}

void FixContactDynamics::unpack_reverse_comm(int n, int* list, double* buf)
{
  int m = 0;
  if (reverse_field == ReverseField::virial) {
    for (int k = 0; k < n; k++)
      for (const int c : peratom_virial_components) vatom[list[k]][c] += buf[m++];
    return;
  }
  for (int k = 0; k < n; k++, m += 3) {
    cd::BodyVelocity& velocity = bodies.velocity[body_of_atom[list[k]]];
    velocity.vx += buf[m];
    velocity.vy += buf[m + 1];
    velocity.spin += buf[m + 2];
  }
}

/* ----------------------------------------------------------------------
   restart and per-atom life cycle
------------------------------------------------------------------------- */

namespace {
// The global restart record: a negative version tag (older files start with the iteration
// total, never negative), the totals, the step grid's level and position (-1: none), the time,
// and the grid the level refers to (dt_max, steps per alignment period).
constexpr double restart_version = -3.0;
constexpr double restart_version_without_grid = -2.0;
}  // namespace

void FixContactDynamics::write_restart(FILE* fp)
{
  if (comm->me != 0) return;
  const cd::StepClock& clock = step_grid->clock();
  const bool known = step_grid->on() && clock.known;
  const double elapsed = lammps_time(*update);
  const double record[9] = {
      restart_version, total_iterations,           total_unconverged_steps,
      total_steps,     known ? clock.level : -1.0, known ? static_cast<double>(clock.steps_into_period) : -1.0,
      elapsed,         step_grid->grid().dt_max,   static_cast<double>(step_grid->grid().steps_per_align)};
  const int size = sizeof(record);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(record, sizeof(double), 9, fp);
}

void FixContactDynamics::restart(char* buf)
{
  const auto* record = reinterpret_cast<const double*>(buf);
  const bool versioned = record[0] == restart_version || record[0] == restart_version_without_grid;
  const double* totals = versioned ? record + 1 : record;
  total_iterations = totals[0];
  total_unconverged_steps = totals[1];
  total_steps = totals[2];
  // This LAMMPS version's restart files do not keep the time (the next run would start it at 0),
  // and with a varying step the step count does not give it: the fix keeps it. Files of earlier
  // versions of the fix came from fixed steps: step x dt.
  set_lammps_time(*update, versioned ? totals[5] : static_cast<double>(update->ntimestep) * update->dt);
  // The level and position hold on the grid they were written on only.
  const bool same_grid = record[0] == restart_version && totals[6] == step_grid->grid().dt_max &&
                         static_cast<int>(totals[7]) == step_grid->grid().steps_per_align;
  if (!same_grid || totals[3] < 0.0) return;
  step_grid->restore({static_cast<int>(totals[3]), static_cast<long long>(totals[4]), true});
}

void FixContactDynamics::grow_arrays(int nmax)
{
  impulses->grow(nmax);
  obstacles.grow(nmax);
}

void FixContactDynamics::copy_arrays(int i, int j, int)
{
  impulses->copy(i, j);
  obstacles.copy(i, j);
}

void FixContactDynamics::set_arrays(int i)
{
  impulses->clear(i);
  obstacles.set_start(i, atom->x[i]);
}

// The warm-start row, then the obstacle start.
int FixContactDynamics::pack_exchange(int i, double* buf)
{
  const int n = impulses->pack(i, buf);
  return n + obstacles.pack(i, buf + n);
}

int FixContactDynamics::unpack_exchange(int nlocal, double* buf)
{
  const int n = impulses->unpack(nlocal, buf);
  return n + obstacles.unpack(nlocal, buf + n);
}

int FixContactDynamics::pack_restart(int i, double* buf)
{
  return impulses->pack_restart(i, buf);
}

void FixContactDynamics::unpack_restart(int nlocal, int nth)
{
  double** extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  const int count = ImpulseStore::entries_in(&extra[nlocal][m]);
  if (count > settings.max_contacts)
    error->one(FLERR,
               "Fix contact/dynamics: restart holds {} contacts for atom {}, more than "
               "max_contacts {}",
               count, atom->tag[nlocal], settings.max_contacts);
  impulses->unpack_restart(nlocal, &extra[nlocal][m]);
}

int FixContactDynamics::size_restart(int i)
{
  return impulses->size_restart(i);
}

int FixContactDynamics::maxsize_restart()
{
  return 1 + impulses->width();
}
