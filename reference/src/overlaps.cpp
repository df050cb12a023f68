#include "overlaps.h"

#include <algorithm>
#include <cmath>

#include "io/dump.h"
#include "io/line_source.h"

namespace cdref {

namespace {

// Closer than this (in mean diameters) counts as touching, not overlapping: the wall column
// of in.rain is built of grains that touch exactly, up to rounding.
constexpr double kTouching = 1e-9;

struct Disk {
  double x, y, r;
};

// Calls visit(i, j) once for every pair closer than the largest contact distance, with cells
// of that size (periodic in x when asked).
template <class Visit>
void for_near_pairs(const std::vector<Disk>& disks, double xlo, double length_x, bool periodic_x, Visit visit)
{
  double rmax = 0, ylo = disks.front().y, yhi = ylo;
  for (const auto& d : disks) {
    rmax = std::max(rmax, d.r);
    ylo = std::min(ylo, d.y);
    yhi = std::max(yhi, d.y);
  }
  const double cell = 2 * rmax;
  const long nx = std::max(1L, static_cast<long>(length_x / cell));
  const long ny = std::max(1L, static_cast<long>((yhi - ylo) / cell) + 1);
  if (nx < 3 || cell <= 0) {  // a small box: every pair (the periodic neighbours would repeat)
    for (size_t i = 0; i < disks.size(); ++i)
      for (size_t j = i + 1; j < disks.size(); ++j) visit(i, j);
    return;
  }
  std::vector<std::vector<size_t>> cells(static_cast<size_t>(nx * ny));
  auto column = [&](double x) {
    long c = static_cast<long>(std::floor((x - xlo) / length_x * nx));
    return ((c % nx) + nx) % nx;
  };
  for (size_t i = 0; i < disks.size(); ++i) {
    long cy = std::min(ny - 1, static_cast<long>((disks[i].y - ylo) / cell));
    cells[static_cast<size_t>(cy * nx + column(disks[i].x))].push_back(i);
  }
  for (long cy = 0; cy < ny; ++cy)
    for (long cx = 0; cx < nx; ++cx) {
      const auto& here = cells[static_cast<size_t>(cy * nx + cx)];
      // Half of the 3x3 neighbourhood: the cell itself, then (+1,0), (-1,+1), (0,+1), (+1,+1).
      static const long offsets[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
      for (size_t a = 0; a < here.size(); ++a)
        for (size_t b = a + 1; b < here.size(); ++b) visit(here[a], here[b]);
      for (const auto& o : offsets) {
        long ox = cx + o[0], oy = cy + o[1];
        if (oy >= ny) continue;
        if (ox < 0 || ox >= nx) {
          if (!periodic_x) continue;
          ox = (ox + nx) % nx;
        }
        for (size_t i : here)
          for (size_t j : cells[static_cast<size_t>(oy * nx + ox)]) visit(i, j);
      }
    }
}

}  // namespace

OverlapStatistics dump_overlaps(const std::string& path, const OverlapOptions& options)
{
  cdpost::DumpReader reader(path);
  cdpost::DumpFrame frame;
  OverlapStatistics stats;
  std::vector<double> all;
  double sum = 0, sum_of_max = 0;
  while (reader.next(frame)) {
    if (frame.timestep < options.first_timestep) continue;
    if (options.last_timestep >= 0 && frame.timestep > options.last_timestep) break;
    const size_t cx = frame.column_index("x"), cy = frame.column_index("y"), cr = frame.column_index("radius");
    std::vector<Disk> disks(frame.atoms);
    for (size_t a = 0; a < frame.atoms; ++a) disks[a] = {frame.value(a, cx), frame.value(a, cy), frame.value(a, cr)};
    if (disks.empty()) continue;
    const double length_x = frame.xhi - frame.xlo;
    const double floor_y = options.floor_y.value_or(frame.ylo);
    double frame_max = 0;
    auto record = [&](double overlap) {
      overlap /= options.mean_diameter;
      all.push_back(overlap);
      sum += overlap;
      frame_max = std::max(frame_max, overlap);
    };
    for_near_pairs(disks, frame.xlo, length_x, options.periodic_x, [&](size_t i, size_t j) {
      double dx = disks[i].x - disks[j].x, dy = disks[i].y - disks[j].y;
      if (options.periodic_x) dx -= length_x * std::round(dx / length_x);
      const double gap = std::hypot(dx, dy) - disks[i].r - disks[j].r;
      if (gap < -kTouching * options.mean_diameter) record(-gap);
    });
    for (const auto& d : disks)
      if (d.y - d.r < floor_y - kTouching * options.mean_diameter) record(floor_y - (d.y - d.r));
    ++stats.frames;
    sum_of_max += frame_max;
    stats.max = std::max(stats.max, frame_max);
  }
  if (stats.frames == 0)
    throw cdpost::InputError(
        path, 0,
        "no frame between timesteps " + std::to_string(options.first_timestep) + " and " +
            (options.last_timestep < 0 ? std::string("the end") : std::to_string(options.last_timestep)));
  stats.contacts = static_cast<long>(all.size());
  if (!all.empty()) {
    stats.mean = sum / static_cast<double>(all.size());
    const size_t k = static_cast<size_t>(0.99 * static_cast<double>(all.size() - 1));
    std::nth_element(all.begin(), all.begin() + static_cast<long>(k), all.end());
    stats.p99 = all[k];
  }
  stats.mean_of_max = sum_of_max / stats.frames;
  return stats;
}

}  // namespace cdref
