#include "figures/snapshot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

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

// Whether each atom of the frame is an obstacle: its type is one of `types` (none when empty).
std::vector<bool> obstacle_atoms(const DumpFrame& frame, const std::vector<long>& types)
{
  std::vector<bool> obstacle(frame.atoms, false);
  if (types.empty()) return obstacle;
  const size_t type = frame.column_index("type");
  for (size_t atom = 0; atom < frame.atoms; ++atom)
    obstacle[atom] = std::find(types.begin(), types.end(), std::lround(frame.value(atom, type))) != types.end();
  if (std::find(obstacle.begin(), obstacle.end(), true) == obstacle.end()) {
    std::string listed;
    for (long t : types) listed += (listed.empty() ? "" : ",") + std::to_string(t);
    throw InputError(frame.source, frame.line,
                     "no atom of the obstacle type(s) " + listed + " in the frame at timestep " +
                         std::to_string(frame.timestep) + ": check --obstacle-types");
  }
  return obstacle;
}

// The mean of the grains' diameters (obstacles left out), input length units.
double mean_diameter(const DumpFrame& frame, size_t radius, const std::vector<bool>& obstacle)
{
  double sum = 0;
  size_t grains = 0;
  for (size_t atom = 0; atom < frame.atoms; ++atom)
    if (!obstacle[atom]) sum += 2 * frame.value(atom, radius), ++grains;
  if (grains == 0)
    throw InputError(frame.source, frame.line, "no grain in the frame to take the mean diameter from: give --d");
  if (!(sum > 0)) throw InputError(frame.source, frame.line, "the radius column's mean is not positive: give --d");
  return sum / double(grains);
}

// "d ...; periodic in ..." with where each came from.
std::string describe(const Units& used, bool d_from_dump, std::array<bool, 2> periodic, bool periodic_given)
{
  std::ostringstream text;
  if (d_from_dump) text << "d " << used.d_m / used.length_unit_m << " input length units (the dump's mean diameter)";
  else text << "d " << used.d_m << " m (from --d or chute.params)";
  const char* axes = periodic[0] && periodic[1] ? "x and y" : periodic[0] ? "x" : periodic[1] ? "y" : "";
  text << "; " << (*axes ? std::string("periodic in ") + axes : std::string("not periodic"))
       << (periodic_given ? " (from --periodic)" : " (the dump's box bounds)");
  // Reduced input with d from the dump: the dump's length unit is not d (an LJ sigma), g is 1 in it.
  if (used.input == Units::Input::reduced && d_from_dump)
    text << "; input in reduced units (g = 1 in the dump's units)";
  else if (used.input != Units::Input::si) text << "; " << input_units_text(used);
  return text.str();
}

// The canvas and ticks of a picture with equal axes: the plot area takes the shape of the cell,
// its longer side kPlotLongSidePx, so that a tall chute and a flat pour both fill their canvas;
// the margins hold the tick labels, the axis labels, the title and the colour bar.
constexpr double kPlotLongSidePx = 900, kPlotShortSideMinPx = 120;
constexpr double kMarginsWidthPx = 260, kMarginsHeightPx = 130;
// Tick labels at least this far apart: along x a label's width ("-10" and "0" of a 45 d cell
// drawn 300 px wide must not touch), along y and the colour bar a line's height.
constexpr double kTickSpacingAlongXPx = 70, kTickSpacingAlongYPx = 30;

// The smallest step of 1, 2 or 5 times a power of ten that puts ticks `spacing` pixels apart or more.
double tick_step(double span, double pixels, double spacing)
{
  const double least = span * spacing / pixels;
  const double decade = std::pow(10.0, std::floor(std::log10(least)));
  for (double factor : {1.0, 2.0, 5.0, 10.0})
    if (factor * decade >= least) return factor * decade;
  return 10 * decade;
}

void fit_canvas(Figure& figure, Panel& panel, double width, double height, double colour_span)
{
  const double aspect = width / height;
  const double plot_width = aspect >= 1 ? kPlotLongSidePx : kPlotLongSidePx * aspect;
  const double plot_height = aspect >= 1 ? kPlotLongSidePx / aspect : kPlotLongSidePx;
  figure.width_px = static_cast<int>(std::lround(plot_width + kMarginsWidthPx));
  figure.height_px = static_cast<int>(std::lround(std::max(plot_height, kPlotShortSideMinPx) + kMarginsHeightPx));
  panel.x_tick_step = tick_step(width, plot_width, kTickSpacingAlongXPx);
  panel.y_tick_step = tick_step(height, plot_height, kTickSpacingAlongYPx);
  if (colour_span > 0) panel.colour_tick_step = tick_step(colour_span, plot_height, kTickSpacingAlongYPx);
}

}  // namespace

Snapshot snapshot_figure(const SnapshotRequest& request, const Units& units)
{
  const DumpFrame frame = select_frame(request);
  const size_t x = frame.column_index("x"), y = frame.column_index("y");
  const size_t vx = frame.column_index("vx"), radius = frame.column_index("radius");
  const auto obstacle = obstacle_atoms(frame, request.obstacle_types);
  Units used = units;
  if (request.diameter_from_dump) used.d_m = mean_diameter(frame, radius, obstacle) * units.length_unit_m;
  const auto periodic = periodic_xy(frame, request.periodic);
  const double to_d = used.length_unit_m / used.d_m;
  const double to_reduced = used.velocity_unit_mps() / used.reduced_velocity_mps();
  const double z0 = request.wall_tops.value_or(0);
  const double xlo = frame.xlo * to_d, xhi = frame.xhi * to_d, length = xhi - xlo;
  const double zlo = (frame.ylo - z0) * to_d, zhi = (frame.yhi - z0) * to_d, height = zhi - zlo;
  const double margin_x = request.image_fraction * length, margin_z = request.image_fraction * height;
  // The bed-trapping walls stand on the periodic boundary from the floor (the box bottom) to
  // the wall tops z = 0: only a grain whose centre is above them can cross to the other side.
  const bool walls = periodic[0] && request.wall_tops && zlo < 0.0;

  Curve grains{"grains", CurveStyle::Circles, {}, {}, {}, {}, {}};
  Curve images{"periodic images", CurveStyle::ShadedCircles, {}, {}, {}, {}, {}};
  Curve obstacles{"obstacles", CurveStyle::Obstacles, {}, {}, {}, {}, {}};
  for (size_t atom = 0; atom < frame.atoms; ++atom) {
    const double gx = frame.value(atom, x) * to_d, gz = (frame.value(atom, y) - z0) * to_d;
    const double r = frame.value(atom, radius) * to_d, u = frame.value(atom, vx) * to_reduced;
    auto add = [&](Curve& curve, double px, double pz) {
      curve.x.push_back(px);
      curve.y.push_back(pz);
      curve.radius.push_back(r);
      curve.colour.push_back(u);
    };
    add(obstacle[atom] ? obstacles : grains, gx, gz);
    std::vector<double> shift_x{0}, shift_z{0};  // the image's offsets across each periodic side
    if (periodic[0] && !(walls && gz <= 0.0)) {
      if (gx - xlo < margin_x) shift_x.push_back(length);
      if (xhi - gx < margin_x) shift_x.push_back(-length);
    }
    if (periodic[1]) {
      if (gz - zlo < margin_z) shift_z.push_back(height);
      if (zhi - gz < margin_z) shift_z.push_back(-height);
    }
    for (double sx : shift_x)
      for (double sz : shift_z)
        if (sx != 0.0 || sz != 0.0) add(obstacle[atom] ? obstacles : images, gx + sx, gz + sz);
  }
  Panel panel;
  const size_t obstacle_count = static_cast<size_t>(std::count(obstacle.begin(), obstacle.end(), true));
  panel.title = "Cell at timestep " + std::to_string(frame.timestep) + " (" +
                std::to_string(frame.atoms - obstacle_count) + " grains" +
                (obstacle_count ? ", " + std::to_string(obstacle_count) + " obstacle atoms" : std::string()) + ")";
  panel.x_label = "x / d";
  panel.y_label = request.wall_tops ? "z / d" : "y / d";
  panel.colour_label = "u_x / sqrt(g d)";
  panel.equal_axes = true;
  panel.key = "off";
  const double pad_x = periodic[0] ? margin_x : 0.0, pad_z = periodic[1] ? margin_z : 0.0;
  panel.x_range = std::make_pair(xlo - pad_x, xhi + pad_x);
  // A shrink-wrapped top with a minimum (boundary fm) stays where the rain started: above the
  // highest grain there is only empty box, so the picture ends a diameter above it.
  double grains_top = zlo;
  for (const Curve* drawn : {&grains, &obstacles})
    for (size_t i = 0; i < drawn->y.size(); ++i) grains_top = std::max(grains_top, drawn->y[i] + drawn->radius[i]);
  const double shown_top =
      periodic[1] || (grains.y.empty() && obstacles.y.empty()) ? zhi + pad_z : std::min(zhi, grains_top + 1.0);
  panel.y_range = std::make_pair(zlo - pad_z, shown_top);
  panel.curves = {grains};
  if (!images.x.empty()) panel.curves.push_back(images);
  std::string caption = "Snapshot of the cell, grains coloured by x-velocity";
  if (!obstacles.x.empty()) {
    panel.curves.push_back(obstacles);
    std::string types;
    for (long t : request.obstacle_types) types += (types.empty() ? "" : ", ") + std::to_string(t);
    caption += "; obstacles (atom type " + types + ") in grey";
  }
  if (periodic[0] || periodic[1]) caption += "; periodic images shaded";
  if (walls) {
    const double nan = std::numeric_limits<double>::quiet_NaN();  // a break between the two walls
    panel.curves.push_back(
        Curve{"walls", CurveStyle::Walls, {xlo, xlo, nan, xhi, xhi}, {zlo, 0.0, nan, zlo, 0.0}, {}, {}, {}});
    caption += " above the wall tops (z = 0), where grains cross the periodic boundary; the walls in black";
  }
  Figure figure{"snapshot", caption, {}};
  const auto [slowest, fastest] = std::minmax_element(grains.colour.begin(), grains.colour.end());
  const double colour_span = grains.colour.empty() ? 0.0 : *fastest - *slowest;
  fit_canvas(figure, panel, length + 2 * pad_x, shown_top - (zlo - pad_z), colour_span);
  figure.panels = {panel};
  std::string parameters = describe(used, request.diameter_from_dump, periodic, request.periodic.has_value());
  if (obstacle_count) parameters += "; " + std::to_string(obstacle_count) + " obstacle atoms (from --obstacle-types)";
  return {figure, parameters};
}

}  // namespace cdpost
