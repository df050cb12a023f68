#include "fix_contact_dynamics_step_grid.h"

#include <cmath>

#include "atom.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

using namespace LAMMPS_NS;

double LAMMPS_NS::lammps_time(const Update& update)
{
  if (update.ntimestep == 0) return 0.0;
  return update.atime + static_cast<double>(update.ntimestep - update.atimestep) * update.dt;
}

void LAMMPS_NS::set_lammps_time(Update& update, double time)
{
  update.atime = time;
  update.atimestep = update.ntimestep;
}

void StepGridControl::setup(int groupbit)
{
  grid_.travel = travel_fraction_ * neighbor->skin;
  if (!clock_.known) {
    // Without the level and position a restart on this grid left, the grid starts afresh here:
    // only at a whole period, or the level changes would miss the sample times.
    const double time = lammps_time(*update);
    if (!grid_.on_alignment(time))
      error->all(FLERR,
                 "Fix contact/dynamics: the step grid cannot start at time {:.10g} s, not a whole number of "
                 "alignment periods ({:.4g} s); continue from a restart written with the same dt_max and dt_align",
                 time, grid_.period());
    clock_.start(fastest_grain_level(groupbit));
  }
  set_timestep(grid_.step(clock_.level));
}

void StepGridControl::end_of_step(int groupbit)
{
  if (!clock_.advance(grid_)) return;
  clock_.level = fastest_grain_level(groupbit);
  set_timestep(grid_.step(clock_.level));
}

// The level of the grid that keeps the fastest grain's travel per step within the bound; a
// grain too fast for the smallest step stops the run.
int StepGridControl::fastest_grain_level(int groupbit)
{
  struct {
    double speed;
    int tag;
  } local{0.0, 0}, fastest{0.0, 0};
  double** v = atom->v;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double speed = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1]);
    if (speed > local.speed) local = {speed, static_cast<int>(atom->tag[i])};
  }
  MPI_Allreduce(&local, &fastest, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  const int level = grid_.level_for(fastest.speed);
  if (level < 0) {
    const double smallest = grid_.step(grid_.max_level);
    stop_(
        fmt::format("Fix contact/dynamics: atom {} moves at {:.4g} m/s; the smallest step {:.4g} (dt_max/2^{}) "
                    "moves it {:.4g}, more than travel x skin = {:.4g} (restart files written if a restart "
                    "command is set)",
                    fastest.tag, fastest.speed, smallest, grid_.max_level, fastest.speed * smallest, grid_.travel));
  }
  return level;
}

// As fix dt/reset does: time so far at the old step, then the new step everywhere it is kept.
void StepGridControl::set_timestep(double dt)
{
  if (dt == update->dt) return;
  update->update_time();
  update->dt = dt;
  update->dt_default = 0;
  if (force->pair) force->pair->reset_dt();
  for (int f = 0; f < modify->nfix; f++) modify->fix[f]->reset_dt();
}
