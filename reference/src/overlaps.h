// Overlaps that soft contacts reach, measured from dump frames the same way for every model
// (a rigid run should read ~0): all pairs of disks closer than the sum of their radii, with
// the minimum image along a periodic x, and disks below the floor.
#pragma once

#include <optional>
#include <string>

namespace cdref {

struct OverlapOptions {
  double mean_diameter = 5e-4;    // overlaps are reported in this length (input units)
  std::optional<double> floor_y;  // floor height; default: the bottom of each frame's box
  long first_timestep = 0;        // frames before this timestep are skipped
  long last_timestep = -1;        // and after this one (-1: no limit)
  bool periodic_x = true;
};

// Overlap delta = r_i + r_j - |x_i - x_j| (> 0) of every contact, in mean diameters.
struct OverlapStatistics {
  int frames = 0;
  long contacts = 0;       // summed over frames
  double mean = 0;         // mean overlap over all contacts of all frames
  double mean_of_max = 0;  // per-frame largest overlap, averaged over frames
  double max = 0;          // largest overlap of any frame
  double p99 = 0;          // 99th percentile over all contacts
};

// Reads the dump (columns x, y, radius; plain or gzip). Throws an InputError without frames
// in the timestep range.
OverlapStatistics dump_overlaps(const std::string& path, const OverlapOptions& options);

}  // namespace cdref
