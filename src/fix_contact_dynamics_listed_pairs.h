// The pairs of the neighbour list of fix contact/dynamics, each once.
#pragma once

#include "atom.h"
#include "neigh_list.h"
#include "neighbor.h"

namespace LAMMPS_NS {

// Every pair of `list` once, as visit(i, j). A pair across a periodic or rank boundary is listed
// from both sides (newton off): the side with the smaller atom ID takes it, on the rank that
// owns that atom.
template <class Visit>
void for_each_listed_pair(const NeighList& list, const Atom& atom, Visit&& visit)
{
  const tagint* tag = atom.tag;
  const int nlocal = atom.nlocal;
  for (int ii = 0; ii < list.inum; ii++) {
    const int i = list.ilist[ii];
    const int* neighbours = list.firstneigh[i];
    for (int jj = 0; jj < list.numneigh[i]; jj++) {
      const int j = neighbours[jj] & NEIGHMASK;
      if (j >= nlocal && tag[i] > tag[j]) continue;
      visit(i, j);
    }
  }
}

}  // namespace LAMMPS_NS
