#include "fix_contact_dynamics_obstacles.h"

#include "atom.h"
#include "domain.h"
#include "memory.h"

using namespace LAMMPS_NS;

ObstacleMotion::~ObstacleMotion()
{
  memory_->destroy(start_);
}

void ObstacleMotion::grow(int nmax)
{
  memory_->grow(start_, nmax, values_per_atom, "contact/dynamics:obstacle_start");
}

void ObstacleMotion::copy(int from, int to)
{
  start_[to][0] = start_[from][0];
  start_[to][1] = start_[from][1];
}

void ObstacleMotion::set_start(int i, const double* x)
{
  start_[i][0] = x[0];
  start_[i][1] = x[1];
}

int ObstacleMotion::pack(int i, double* buf) const
{
  buf[0] = start_[i][0];
  buf[1] = start_[i][1];
  return values_per_atom;
}

int ObstacleMotion::unpack(int i, const double* buf)
{
  set_start(i, buf);
  return values_per_atom;
}

void ObstacleMotion::find(const Atom& atom, int groupbit, MPI_Comm world)
{
  int here = 0;
  for (int i = 0; i < atom.nlocal && !here; i++) here = (atom.mask[i] & groupbit) ? 0 : 1;
  int anywhere = 0;
  MPI_Allreduce(&here, &anywhere, 1, MPI_INT, MPI_MAX, world);
  present_ = anywhere != 0;
}

void ObstacleMotion::record_starts(const Atom& atom, int groupbit)
{
  for (int i = 0; i < atom.nlocal; i++)
    if (!(atom.mask[i] & groupbit)) set_start(i, atom.x[i]);
}

void ObstacleMotion::measure_travel(const Atom& atom, Domain& domain, int groupbit)
{
  travel_.assign(atom.nlocal + atom.nghost, cd::Displacement{});
  for (int i = 0; i < atom.nlocal; i++) {
    if (atom.mask[i] & groupbit) continue;
    double dx = atom.x[i][0] - start_[i][0], dy = atom.x[i][1] - start_[i][1], dz = 0.0;
    // Nothing moved it: no image, so that it stays exactly at rest.
    if (dx != 0.0 || dy != 0.0) domain.minimum_image(dx, dy, dz);
    travel_[i] = {dx, dy};
  }
}

int ObstacleMotion::pack_travel(int n, const int* list, double* buf) const
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    buf[m++] = travel_[list[k]].dx;
    buf[m++] = travel_[list[k]].dy;
  }
  return m;
}

void ObstacleMotion::unpack_travel(int n, int first, const double* buf)
{
  for (int k = 0; k < n; k++) travel_[first + k] = {buf[2 * k], buf[2 * k + 1]};
}

double ObstacleMotion::memory_usage(int nmax) const
{
  return static_cast<double>(nmax) * values_per_atom * sizeof(double) +
         static_cast<double>(travel_.capacity()) * sizeof(cd::Displacement);
}
