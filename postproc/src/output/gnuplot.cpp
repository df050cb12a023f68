#include "output/gnuplot.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "output/results.h"

namespace cdpost {

Curve make_curve(const std::string& title, CurveStyle style, std::vector<double> x, std::vector<double> y)
{
  Curve curve;
  curve.title = title;
  curve.style = style;
  curve.x = std::move(x);
  curve.y = std::move(y);
  return curve;
}

namespace {

std::string quoted(const std::string& text)
{
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string block_name(size_t panel, size_t curve)
{
  return "$p" + std::to_string(panel) + "c" + std::to_string(curve);
}

void write_data_block(std::ostream& out, const std::string& name, const Curve& curve)
{
  out << name << " << EOD\n";
  for (size_t i = 0; i < curve.x.size(); ++i) {
    if (std::isnan(curve.x[i])) {  // a blank line breaks a line plot
      out << '\n';
      continue;
    }
    out << curve.x[i] << ' ' << curve.y[i];
    if (curve.style == CurveStyle::ErrorBars || curve.style == CurveStyle::LinesBand) out << ' ' << curve.y_error[i];
    if (curve.style == CurveStyle::Circles || curve.style == CurveStyle::ShadedCircles)
      out << ' ' << curve.radius[i] << ' ' << curve.colour[i];
    if (curve.style == CurveStyle::Obstacles) out << ' ' << curve.radius[i];
    if (curve.style == CurveStyle::Map) out << ' ' << curve.colour[i];
    if (curve.style == CurveStyle::Vectors) out << ' ' << curve.dx[i] << ' ' << curve.dy[i];
    out << '\n';
  }
  out << "EOD\n";
}

// The curve at position `index` of its panel: its own line type, else (a LinesBand, for both its
// band and its line) the line type index + 1; other styles take gnuplot's by position.
std::string plot_clause(const Curve& curve, const std::string& block, size_t index)
{
  std::string with;
  const std::string colour = " lt " + std::to_string(curve.line_type ? curve.line_type : index + 1);
  const std::string own_colour = curve.line_type ? colour : "";
  const std::string point = " pt " + std::to_string(curve.point_type ? curve.point_type : 7);
  const std::string dash = curve.dashed ? " dt 2" : "";
  switch (curve.style) {
    case CurveStyle::Points: with = "using 1:2 with points" + point + " ps 1" + own_colour; break;
    case CurveStyle::Lines: with = "using 1:2 with lines lw 2" + own_colour + dash; break;
    case CurveStyle::LinesPoints: with = "using 1:2 with linespoints" + point + " lw 1.5" + own_colour; break;
    case CurveStyle::ErrorBars: with = "using 1:2:3 with yerrorbars" + point + own_colour; break;
    case CurveStyle::Circles: with = "using 1:2:3:4 with circles lc palette fs solid 1.0 noborder"; break;
    case CurveStyle::ShadedCircles:
      with = "using 1:2:3:4 with circles lc palette fs transparent solid 0.3 noborder";
      break;
    case CurveStyle::Obstacles:
      with = "using 1:2:3 with circles lc rgb 'grey50' fs solid 1.0 border lc rgb 'grey30'";
      break;
    case CurveStyle::Walls: with = "using 1:2 with lines lw 3 lc rgb 'black'"; break;
    case CurveStyle::LinesBand:
      with = "using 1:($2-$3):($2+$3) with filledcurves fs transparent solid 0.2 noborder" + colour + " notitle, " +
             block + " using 1:2 with lines lw 2" + colour + dash;
      break;
    case CurveStyle::Map: with = "using 1:2:3 with image"; break;
    case CurveStyle::Vectors:
      with = "using 1:2:3:4 with vectors head filled size screen 0.008,20 lc rgb 'black'";
      break;
  }
  return block + " " + with + (curve.title.empty() ? " notitle" : " title " + quoted(curve.title));
}

void write_range(std::ostream& out, const char* axis, const std::optional<std::pair<double, double>>& range)
{
  if (range) out << "set " << axis << "range [" << range->first << ":" << range->second << "]\n";
}

void write_panel(std::ostream& out, const Panel& panel, size_t index, bool multiplot)
{
  out << "reset\nset termoption noenhanced\nset grid\n";
  if (multiplot)
    out << "set origin " << panel.origin_x << "," << panel.origin_y << "\nset size " << panel.width << ","
        << panel.height << "\n";
  out << "set title " << quoted(panel.title) << "\nset xlabel " << quoted(panel.x_label) << "\nset ylabel "
      << quoted(panel.y_label) << "\nset key " << panel.key << "\n";
  if (panel.log_x) out << "set logscale x\n";
  if (panel.log_y) out << "set logscale y\n";
  if (panel.equal_axes) out << "set size ratio -1\n";
  if (!panel.colour_label.empty())
    out << "set palette rgb 33,13,10\nset cblabel " << quoted(panel.colour_label) << "\n";
  write_range(out, "x", panel.x_range);
  write_range(out, "y", panel.y_range);
  if (panel.x_tick_step) out << "set xtics " << *panel.x_tick_step << "\n";
  if (panel.y_tick_step) out << "set ytics " << *panel.y_tick_step << "\n";
  if (panel.colour_tick_step) out << "set cbtics " << *panel.colour_tick_step << "\n";
  if (panel.x_band)
    out << "set object 1 rect from " << panel.x_band->first << ", graph 0 to " << panel.x_band->second
        << ", graph 1 behind fc rgb '#e4e4f0' fs solid noborder\n";
  out << "plot ";
  for (size_t c = 0; c < panel.curves.size(); ++c)
    out << (c ? ", \\\n     " : "") << plot_clause(panel.curves[c], block_name(index, c), c);
  out << "\n";
}

void write_body(std::ostream& out, const Figure& figure)
{
  bool multiplot = figure.panels.size() > 1;
  if (multiplot) out << "set multiplot\n";
  for (size_t p = 0; p < figure.panels.size(); ++p) write_panel(out, figure.panels[p], p, multiplot);
  if (multiplot) out << "unset multiplot\n";
}

}  // namespace

std::string gnuplot_script(const Figure& figure)
{
  std::ostringstream out;
  out.precision(8);
  out << "# " << figure.caption << "\n# Written by cdpost; run `gnuplot " << figure.name << ".gp`.\n";
  for (size_t p = 0; p < figure.panels.size(); ++p)
    for (size_t c = 0; c < figure.panels[p].curves.size(); ++c)
      write_data_block(out, block_name(p, c), figure.panels[p].curves[c]);
  const std::string size = std::to_string(figure.width_px) + "," + std::to_string(figure.height_px);
  out << "set terminal pngcairo size " << size << " font ',10'\nset output '" << figure.name << ".png'\n";
  write_body(out, figure);
  out << "set terminal svg size " << size << " font ',10' background '#ffffff'\nset output '" << figure.name
      << ".svg'\n";
  write_body(out, figure);
  out << "unset output\n";
  return out.str();
}

std::optional<std::string> render_figure(const Figure& figure, const std::string& directory)
{
  const std::string script = directory + "/" + figure.name + ".gp";
  open_output(script) << gnuplot_script(figure);
  static const bool have_gnuplot = std::system("command -v gnuplot >/dev/null 2>&1") == 0;
  if (!have_gnuplot)
    return "gnuplot not found (install gnuplot-nox): " + figure.name + " not drawn, script kept in " + script;
  const std::string log = directory + "/" + figure.name + ".log";
  std::string command = "cd '" + directory + "' && gnuplot '" + figure.name + ".gp' >'" + figure.name + ".log' 2>&1";
  if (std::system(command.c_str()) != 0) return "gnuplot failed on " + script + " (see " + log + ")";
  std::remove(log.c_str());
  return std::nullopt;
}

}  // namespace cdpost
