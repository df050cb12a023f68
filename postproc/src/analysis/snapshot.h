// A picture of the cell from a LAMMPS dump: grains coloured by their x-velocity, the
// bed-trapping walls on the periodic boundary (from the box bottom up to the wall tops z0),
// and the periodic images beyond the x boundaries shaded where grains can cross, above the
// wall tops (everywhere when there are no walls, z0 at or below the box bottom). The dump is
// streamed.
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
// z = y - z0, colour in sqrt(g d)): curves "grains", "periodic images" (when any) and
// "walls" (when z0 is above the box bottom).
Figure snapshot_figure(const SnapshotRequest& request, const Units& units, double z0);

}  // namespace cdpost
