// The exchange across MPI ranks between the sweeps of fix contact/dynamics (cd::SweepExchange):
// the velocity changes of ghosts summed into their owners (reverse comm), the owners' velocities
// copied to the ghosts (forward comm), the norm's sums reduced over the ranks.
#pragma once

#include "cd/solver.h"
#include "pointers.h"

namespace LAMMPS_NS {
class Fix;

class RankExchange : public cd::SweepExchange, protected Pointers {
 public:
  // `fix` packs and unpacks the velocities; `norm` is its solver's.
  RankExchange(LAMMPS* lmp, Fix& fix, cd::ConvergenceNorm norm) : Pointers(lmp), fix_(fix), norm_(norm) {}
  void after_sweep(cd::SweepChange& change) override;
  bool on_any_rank(bool here) override;
  void share_velocities() override;
  void sum_over_ranks(double* values, int count) override;

 private:
  Fix& fix_;
  cd::ConvergenceNorm norm_;
};

}  // namespace LAMMPS_NS
