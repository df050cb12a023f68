#include "analysis/snapshot.h"

#include <limits>

#include "io/dump.h"
#include "io/progress.h"

namespace cdpost {

namespace {

DumpFrame select_frame(const SnapshotRequest& request)
{
  DumpReader reader(request.dump_path);
  Progress progress("reading " + request.dump_path, true, request.progress);
  DumpFrame frame, chosen;
  bool found = false;
  while (reader.next(frame)) {
    progress.update(reader.source().fraction_read(), "timestep " + std::to_string(frame.timestep));
    if (!request.timestep || frame.timestep == *request.timestep) {
      std::swap(chosen, frame);
      found = true;
      if (request.timestep) break;
    }
  }
  if (!found)
    throw InputError(
        request.dump_path, 0,
        request.timestep ? "no frame at timestep " + std::to_string(*request.timestep) : "no frame (empty dump)");
  return chosen;
}

}  // namespace

Figure snapshot_figure(const SnapshotRequest& request, const Units& units, double z0)
{
  const DumpFrame frame = select_frame(request);
  const size_t x = frame.column_index("x"), y = frame.column_index("y");
  const size_t vx = frame.column_index("vx"), radius = frame.column_index("radius");
  const double to_d = units.length_unit_m / units.d_m;
  const double to_reduced = units.velocity_unit_mps() / units.reduced_velocity_mps();
  const double length = (frame.xhi - frame.xlo) * to_d, xlo = frame.xlo * to_d, xhi = frame.xhi * to_d;
  const double margin = request.image_fraction * length;
  // The bed-trapping walls stand on the periodic boundary from the floor (the box bottom) to
  // the wall tops z = 0: only a grain whose centre is above them can cross to the other side.
  const double floor_z = (frame.ylo - z0) * to_d;
  const bool walls = floor_z < 0.0;

  Curve grains{"grains", CurveStyle::Circles, {}, {}, {}, {}, {}};
  Curve images{"periodic images", CurveStyle::ShadedCircles, {}, {}, {}, {}, {}};
  for (size_t atom = 0; atom < frame.atoms; ++atom) {
    const double gx = frame.value(atom, x) * to_d, gz = (frame.value(atom, y) - z0) * to_d;
    const double r = frame.value(atom, radius) * to_d, u = frame.value(atom, vx) * to_reduced;
    auto add = [&](Curve& curve, double px) {
      curve.x.push_back(px);
      curve.y.push_back(gz);
      curve.radius.push_back(r);
      curve.colour.push_back(u);
    };
    add(grains, gx);
    if (walls && gz <= 0.0) continue;
    if (gx - xlo < margin) add(images, gx + length);
    if (xhi - gx < margin) add(images, gx - length);
  }
  Panel panel;
  panel.title = "Cell at timestep " + std::to_string(frame.timestep) + " (" + std::to_string(frame.atoms) + " grains)";
  panel.x_label = "x / d";
  panel.y_label = "z / d";
  panel.colour_label = "u_x / sqrt(g d)";
  panel.equal_axes = true;
  panel.key = "off";
  panel.x_range = std::make_pair(xlo - margin, xhi + margin);
  panel.curves = {grains};
  if (!images.x.empty()) panel.curves.push_back(images);
  std::string caption = "Snapshot of the cell, grains coloured by x-velocity; periodic images shaded";
  if (walls) {
    const double nan = std::numeric_limits<double>::quiet_NaN();  // a break between the two walls
    panel.curves.push_back(
        Curve{"walls", CurveStyle::Walls, {xlo, xlo, nan, xhi, xhi}, {floor_z, 0.0, nan, floor_z, 0.0}, {}, {}, {}});
    caption += " above the wall tops (z = 0), where grains cross the periodic boundary; the walls in black";
  }
  Figure figure{"snapshot", caption, {panel}, 1400, 700};
  return figure;
}

}  // namespace cdpost
