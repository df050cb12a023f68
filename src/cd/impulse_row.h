// The impulses a body carries from one step to the next (the warm start), as one flat row of
// doubles that a host can grow, copy, exchange and restart with the body:
//     [count, partner_1, p_n_1, p_t_1, ..., partner_count, p_n_count, p_t_count]
// A partner is the host's key of the other body of the pair (cd::PairKey::partner).
#pragma once

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
inline Local2 find(const double* row, double partner)
{
  const int count = entries(row);
  for (int k = 0; k < count; k++) {
    const double* entry = row + 1 + entry_width * k;
    if (entry[0] == partner) return {entry[1], entry[2]};
  }
  return {};
}

// Stores `impulse` for `partner` after the others; false (nothing stored) if the row already
// holds `capacity` entries.
inline bool append(double* row, int capacity, double partner, Local2 impulse)
{
  const int count = entries(row);
  if (count >= capacity) return false;
  double* entry = row + 1 + entry_width * count;
  entry[0] = partner;
  entry[1] = impulse.n;
  entry[2] = impulse.t;
  row[0] = count + 1;
  return true;
}

}  // namespace cd::impulse_row
