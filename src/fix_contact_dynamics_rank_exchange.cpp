#include "fix_contact_dynamics_rank_exchange.h"

#include "comm.h"

using namespace LAMMPS_NS;

// A sweep changes the velocities of owned bodies and of ghost bodies touched by contacts this
// rank solves: the changes of ghosts are summed into their owners, then every ghost takes its
// owner's velocity again.
void RankExchange::share_velocities()
{
  comm->reverse_comm_fix(&fix_);
  comm->forward_comm_fix(&fix_);
}

void RankExchange::sum_over_ranks(double* values, int count)
{
  MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_SUM, world);
}

void RankExchange::after_sweep(cd::SweepChange& change)
{
  share_velocities();
  double sums[5] = {change.sum_change_sq, change.sum_scale_sq, change.sum_scale, change.contacts, change.face_changes};
  MPI_Allreduce(MPI_IN_PLACE, sums, 5, MPI_DOUBLE, MPI_SUM, world);
  // The largest change matters to the maximum norm only: spare the quadratic one a reduction.
  if (norm_ == cd::ConvergenceNorm::maximum)
    MPI_Allreduce(MPI_IN_PLACE, &change.max_change, 1, MPI_DOUBLE, MPI_MAX, world);
  change.sum_change_sq = sums[0];
  change.sum_scale_sq = sums[1];
  change.sum_scale = sums[2];
  change.contacts = sums[3];
  change.face_changes = sums[4];
}

bool RankExchange::on_any_rank(bool here)
{
  int mine = here ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, world);
  return any != 0;
}
