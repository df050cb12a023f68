// A picture of the cell from a LAMMPS dump: grains coloured by their x-velocity, obstacles (the
// atoms of the types given, e.g. a ring moved by fix move outside the fix's group) in grey, the
// bed-trapping walls on the periodic boundary (from the box bottom up to the wall tops z0), and
// the periodic images shaded across the periodic boundaries only: across x above the wall tops
// (everywhere when there are no walls), across y when y is periodic. The diameter d that lengths
// are measured in and the periodicity come from the caller when given, else from the dump (the
// mean of its radius column, its "ITEM: BOX BOUNDS" flags). The dump is streamed.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "analysis/run_analysis.h"
#include "output/gnuplot.h"

namespace cdpost {

struct SnapshotRequest {
  std::string dump_path;
  std::optional<long> timestep;  // the frame to draw; the last one if not given
  double image_fraction = 0.15;  // width of the shaded periodic images, fraction of the box side
  bool progress = false;
  bool diameter_from_dump = false;              // d is the dump's mean diameter, not units.d_m
  std::optional<std::array<bool, 2>> periodic;  // x, y periodic; else the dump's box bounds flags
  std::optional<double> wall_tops;              // z0, input length units: walls below it, z = y - z0
  std::vector<long> obstacle_types;             // atom types drawn as obstacles (the dump's type column)
};

struct Snapshot {
  Figure figure;
  std::string parameters;  // one line: d and the periodicity used, and where each came from
};

// Figure named "snapshot" of the chosen frame (dump columns x y vx radius; lengths in d,
// z = y - z0 (y without wall tops), colour in sqrt(g d)): curves "grains", "periodic images"
// (when any), "obstacles" (when obstacle types are given: the column type too) and "walls" (when
// the wall tops are above the box bottom). InputError when the periodicity is neither given nor
// in the dump, d is taken from a dump without grains, or no atom has an obstacle type.
Snapshot snapshot_figure(const SnapshotRequest& request, const Units& units);

}  // namespace cdpost
