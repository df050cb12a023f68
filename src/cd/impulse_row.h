// The impulses a body carries from one step to the next (the warm start), as one flat row of
// doubles that a host can grow, copy, exchange and restart with the body:
//     [count, partner_1, p_n_1, p_t_1, ..., partner_count, p_n_count, p_t_count]
// A partner is the host's id of the other body of the pair (cd::PairKey::partner), kept as a
// double because the row is one of LAMMPS's per-atom arrays: exact for ids below 2^53 (atom IDs
// and wall slots are far below). It is converted here and nowhere else.
#pragma once

#include <cstdint>

#include "cd/coulomb_local.h"

namespace cd::impulse_row {

inline constexpr int entry_width = 3;  // partner, p_n, p_t

// Doubles a row needs for `entries` entries.
inline int width(int entries)
{
  return 1 + entry_width * entries;
}

inline int entries(const double* row)
{
  return static_cast<int>(row[0]);
}

// Doubles of the row in use (what to copy, exchange or write to a restart).
inline int used(const double* row)
{
  return width(entries(row));
}

inline void clear(double* row)
{
  row[0] = 0.0;
}

// The impulse stored for `partner`; {0, 0} if none.
inline Local2 find(const double* row, std::int64_t partner)
{
  const double stored_partner = static_cast<double>(partner);
  const int count = entries(row);
  for (int k = 0; k < count; k++) {
    const double* entry = row + 1 + entry_width * k;
    if (entry[0] == stored_partner) return {entry[1], entry[2]};
  }
  return {};
}

// Stores `impulse` for `partner` after the others; false (nothing stored) if the row already
// holds `capacity` entries.
inline bool append(double* row, int capacity, std::int64_t partner, Local2 impulse)
{
  const int count = entries(row);
  if (count >= capacity) return false;
  double* entry = row + 1 + entry_width * count;
  entry[0] = static_cast<double>(partner);
  entry[1] = impulse.n;
  entry[2] = impulse.t;
  row[0] = count + 1;
  return true;
}

}  // namespace cd::impulse_row
