// A picture of the cell from a LAMMPS dump: grains coloured by their x-velocity, with the
// periodic images beyond the x boundaries shaded. The dump is streamed.
#pragma once

#include <optional>
#include <string>

#include "analysis/run_analysis.h"
#include "output/gnuplot.h"

namespace cdpost {

struct SnapshotRequest {
  std::string dump_path;
  std::optional<long> timestep;  // the frame to draw; the last one if not given
  double image_fraction = 0.15;  // width of the shaded periodic images, fraction of L
  bool progress = false;
};

// Figure named "snapshot" of the chosen frame (dump columns x y vx radius; lengths in d,
// z = y - z0, colour in sqrt(g d)).
Figure snapshot_figure(const SnapshotRequest& request, const Units& units, double z0);

}  // namespace cdpost
