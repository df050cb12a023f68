// The warm-start store of fix contact/dynamics: one cd::impulse_row per atom, a LAMMPS per-atom
// array that travels with the atoms between ranks and into restarts. The atom with the smaller ID
// of a pair (or the atom touching a wall) keeps the pair's impulses, keyed by partner.
#pragma once

#include "cd/detection.h"

namespace LAMMPS_NS {
class Memory;

class ImpulseStore {
 public:
  ImpulseStore(Memory* memory, int max_contacts);
  ~ImpulseStore();
  ImpulseStore(const ImpulseStore&) = delete;
  ImpulseStore& operator=(const ImpulseStore&) = delete;

  int max_contacts() const { return max_contacts_; }
  int width() const { return width_; }  // doubles a row may take

  // The per-atom life cycle, as a fix's grow_arrays, copy_arrays, set_arrays, pack_exchange and
  // unpack_exchange (each returns the values it packed or read).
  void grow(int nmax);
  void copy(int from, int to);
  void clear(int i);
  int pack(int i, double* buf) const;
  int unpack(int i, const double* buf);
  // In a restart: the values written (LAMMPS's convention: the first counts them all), and a
  // row read back from `values` (its contacts; a row above max_contacts is not read: 0 returned
  // is no refusal, the caller checks entries_in first).
  int pack_restart(int i, double* buf) const;
  int size_restart(int i) const;
  static int entries_in(const double* values);
  void unpack_restart(int i, const double* values);

  // The impulse the pair carried ({0, 0} if none).
  cd::Local2 carried(const cd::PairKey& key) const;
  // Stores the pair's impulse; false (nothing stored) if its row holds max_contacts already.
  bool append(const cd::PairKey& key, cd::Local2 impulse);

  double memory_usage(int nmax) const;

 private:
  Memory* memory_;
  int max_contacts_;
  int width_;
  double** rows_ = nullptr;
};

}  // namespace LAMMPS_NS
