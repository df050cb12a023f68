// Obstacles of fix contact/dynamics (atoms outside its group) that other fixes move (fix move,
// fix nve, fix deform's remap x, ...), met at the instant the grains are met.
//
// A step detects the grains' contacts at x_m = x_n + (1 - theta) dt v_n, the fraction 1 - theta
// of the step. An obstacle that travelled by s = x_now - x_start since the previous solve
// (x_start: where it stood then) is placed at the same fraction of its own step,
// x_start + (1 - theta) s = x_now - theta s, with velocity s / dt: the step's corrector then
// ends it where the other fix put it. An obstacle nothing moved (s exactly zero) stays where it
// is with its own velocity, a surface velocity of its contacts.
#pragma once

#include <vector>

#include "cd/contact_geometry.h"
#include "cd/step.h"

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

  // Where every owned obstacle stands now: the start of its next step.
  void record_starts(const Atom& atom, int groupbit);
  // The travel of every owned obstacle since its start (nearest periodic image); grains and
  // ghosts get zero, ghosts then theirs through pack_travel and unpack_travel (forward comm).
  void measure_travel(const Atom& atom, Domain& domain, int groupbit);
  int pack_travel(int n, const int* list, double* buf) const;
  void unpack_travel(int n, int first, const double* buf);

  const cd::Displacement& travel(int i) const { return travel_[i]; }
  // The disk of atom i (at x now) at the instant of the grains' x_m.
  cd::Disk disk_at_solve(int i, const double* x, double radius, double theta) const
  {
    const cd::Displacement& s = travel_[i];
    return {x[0] - theta * s.dx, x[1] - theta * s.dy, radius};
  }
  // The step's velocity of obstacle i: its travel over dt if it moved, else `own`.
  cd::BodyVelocity velocity(int i, const cd::BodyVelocity& own, double dt) const
  {
    const cd::Displacement& s = travel_[i];
    if (s.dx == 0.0 && s.dy == 0.0) return own;
    return {s.dx / dt, s.dy / dt, own.spin};
  }
  double memory_usage(int nmax) const;

 private:
  Memory* memory_;
  double** start_ = nullptr;              // per owned atom: where the last solve found it
  std::vector<cd::Displacement> travel_;  // per owned and ghost atom, this step
};

}  // namespace LAMMPS_NS
