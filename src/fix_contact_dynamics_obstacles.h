// Obstacles of fix contact/dynamics (atoms outside its group) that other fixes move (fix move,
// fix nve, fix deform's remap x, ...), met at the instant the grains are met: each one's start
// (where the previous solve found it) travels with the atom, its travel since then is measured
// here, and the core places it (cd::obstacle_at_solve, cd::obstacle_velocity).
#pragma once

#include <mpi.h>

#include <vector>

#include "cd/kinematics.h"

namespace LAMMPS_NS {
class Atom;
class Domain;
class Memory;

class ObstacleMotion {
 public:
  static constexpr int values_per_atom = 2;  // x, y of the atom's start

  explicit ObstacleMotion(Memory* memory) : memory_(memory) {}
  ~ObstacleMotion();
  ObstacleMotion(const ObstacleMotion&) = delete;
  ObstacleMotion& operator=(const ObstacleMotion&) = delete;

  // The per-atom starts' life cycle, as a fix's grow_arrays, copy_arrays, set_arrays,
  // pack_exchange and unpack_exchange (each returns the values it packed or read).
  void grow(int nmax);
  void copy(int from, int to);
  void set_start(int i, const double* x);
  int pack(int i, double* buf) const;
  int unpack(int i, const double* buf);

  // Whether any atom on any rank lies outside the group: without, nothing here runs.
  void find(const Atom& atom, int groupbit, MPI_Comm world);
  bool present() const { return present_; }

  // Where every owned obstacle stands now: the start of its next step.
  void record_starts(const Atom& atom, int groupbit);
  // The travel of every owned obstacle since its start (nearest periodic image); grains and
  // ghosts get zero, ghosts then theirs through pack_travel and unpack_travel (forward comm).
  void measure_travel(const Atom& atom, Domain& domain, int groupbit);
  int pack_travel(int n, const int* list, double* buf) const;
  void unpack_travel(int n, int first, const double* buf);

  const cd::Displacement& travel(int i) const { return travel_[i]; }
  // The disk of atom i, `now`, at the instant of the grains' x_m.
  cd::Disk disk_at_solve(int i, const cd::Disk& now, const cd::StepParameters& step) const
  {
    return present_ ? cd::obstacle_at_solve(now, travel_[i], step) : now;
  }
  // The step's velocity of obstacle i (`own`: LAMMPS's).
  cd::BodyVelocity velocity(int i, const cd::BodyVelocity& own, double dt) const
  {
    return cd::obstacle_velocity(travel_[i], own, dt);
  }
  double memory_usage(int nmax) const;

 private:
  Memory* memory_;
  bool present_ = false;
  double** start_ = nullptr;              // per owned atom: where the last solve found it
  std::vector<cd::Displacement> travel_;  // per owned and ghost atom, this step
};

}  // namespace LAMMPS_NS
