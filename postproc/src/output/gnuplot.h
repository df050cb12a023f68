// Figures drawn by gnuplot (Debian's gnuplot-nox): each figure is written as one
// self-contained script NAME.gp (data inline), then rendered to NAME.png and NAME.svg.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cdpost {

// Obstacles: circles in grey, off the palette (atoms that are not grains, e.g. a ring moved by
// fix move). Walls: black lines; in Lines and Walls a NaN point breaks the line. LinesBand: a line with a
// shaded band y ± y_error of the same colour (a fitted curve and its confidence band). Map: a
// regular grid of x, y coloured by `colour` (gnuplot's image), one NaN point between scans of
// constant x. Vectors: arrows from (x, y) by (dx, dy).
enum class CurveStyle {
  Points,
  Lines,
  LinesPoints,
  ErrorBars,
  Circles,
  ShadedCircles,
  Obstacles,
  Walls,
  LinesBand,
  Map,
  Vectors
};

struct Curve {
  std::string title;
  CurveStyle style = CurveStyle::Points;
  std::vector<double> x, y;
  std::vector<double> y_error;           // ErrorBars, LinesBand
  std::vector<double> radius;            // Circles, Obstacles: radius in x-axis units
  std::vector<double> colour;            // Circles, Map: value mapped on the palette
  std::vector<double> dx = {}, dy = {};  // Vectors: the arrows
  // gnuplot's line type (its colour) and point type; 0: by the curve's position, filled circles.
  int line_type = 0, point_type = 0;
  bool dashed = false;  // Lines, LinesBand
};

// The curve through (x, y) drawn in `style`, titled in the key.
Curve make_curve(const std::string& title, CurveStyle style, std::vector<double> x, std::vector<double> y);

// A curve of one friction coefficient (a series' figures, the source drawn over them).
struct FrictionCurve {
  double mu = 0;
  Curve curve;
};

struct Panel {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  bool equal_axes = false;
  std::string colour_label;  // for Circles: the colour bar's label
  std::optional<std::pair<double, double>> x_range, y_range;
  std::optional<std::pair<double, double>> x_band;  // shaded interval, e.g. the stationary window
  std::optional<double> x_tick_step, y_tick_step;   // distance between ticks; gnuplot's choice if not set
  std::optional<double> colour_tick_step;           // the same on the colour bar
  std::string key = "top left";
  std::vector<Curve> curves;
  // Placement in the canvas (fractions); the default fills it.
  double origin_x = 0, origin_y = 0, width = 1, height = 1;
};

struct Figure {
  std::string name;  // file stem
  std::string caption;
  std::vector<Panel> panels;
  int width_px = 900, height_px = 650;
};

// The gnuplot script for `figure`, writing NAME.png and NAME.svg in the working directory.
std::string gnuplot_script(const Figure& figure);

// Writes DIR/NAME.gp and runs gnuplot in DIR. Returns a problem description, or nothing on
// success (missing gnuplot or a failed run is reported, not thrown: figures are optional).
std::optional<std::string> render_figure(const Figure& figure, const std::string& directory);

}  // namespace cdpost
