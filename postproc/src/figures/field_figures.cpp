#include "figures/field_figures.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cdpost {

namespace {

std::string number(double value)
{
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

std::string with_unit(const std::string& name, const std::string& unit)
{
  return unit.empty() ? name : name + " (" + unit + ")";
}

// "4 frames, timesteps 1000 to 4000; Gaussian kernel ..." for every caption and title.
std::string averaging(const Fields& fields)
{
  return std::to_string(fields.frames) + " frames, timesteps " + std::to_string(fields.first_step) + " to " +
         std::to_string(fields.last_step) + "; " + fields.kernel_description;
}

// A map of one column, its nodes in scans of constant x, with the velocity arrows if asked.
Figure map_figure(const Fields& fields, const std::string& column, const std::string& title, bool arrows)
{
  const auto& axes = fields.axes;
  const auto& values = fields.column(column);
  const auto& ux = fields.column("ux").values;
  const auto& uy = fields.column("uy").values;
  const size_t nx = axes[0].cells, ny = axes[1].cells;
  const auto& node_x = fields.column("x").values;
  const auto& node_y = fields.column("y").values;
  Curve map;
  if (fields.is_polar()) {  // a disk a node, as wide as its cell
    map.style = CurveStyle::Circles;
    const double dr = axes[1].spacing(), dt = axes[0].spacing();
    for (size_t k = 0; k < node_x.size(); ++k) {
      if (!std::isfinite(values.values[k])) continue;
      map.x.push_back(node_x[k]);
      map.y.push_back(node_y[k]);
      map.radius.push_back(0.55 * std::min(dr, axes[1].node(k / nx) * dt));
      map.colour.push_back(values.values[k]);
    }
  } else {
    map.style = CurveStyle::Map;
    for (size_t i = 0; i < nx; ++i) {
      if (i) map.x.push_back(NAN), map.y.push_back(NAN), map.colour.push_back(NAN);
      for (size_t j = 0; j < ny; ++j) {
        map.x.push_back(axes[0].node(i));
        map.y.push_back(axes[1].node(j));
        map.colour.push_back(values.values[i + nx * j]);
      }
    }
  }
  Panel panel;
  panel.title = title + " (" + std::to_string(fields.frames) + " frames)";
  panel.x_label = with_unit("x", fields.settings.units.length);
  panel.y_label = with_unit("y", fields.settings.units.length);
  panel.colour_label = with_unit(column, values.unit);
  panel.equal_axes = true;
  panel.key = "off";
  const auto [x_low, x_high] = std::minmax_element(node_x.begin(), node_x.end());
  const auto [y_low, y_high] = std::minmax_element(node_y.begin(), node_y.end());
  const double pad = fields.is_polar() ? 0.5 * axes[1].spacing() : 0.5 * axes[0].spacing();
  const double pad_y = fields.is_polar() ? pad : 0.5 * axes[1].spacing();
  panel.x_range = std::make_pair(*x_low - pad, *x_high + pad);
  panel.y_range = std::make_pair(*y_low - pad_y, *y_high + pad_y);
  panel.curves.push_back(map);
  std::string caption = title + " on " + std::to_string(nx) + " x " + std::to_string(ny) +
                        (fields.is_polar() ? " polar cells (sectors x rings); " : " nodes; ") + averaging(fields);
  if (arrows) {
    // About 24 arrows along the longer side, the fastest as long as their spacing.
    const size_t stride = std::max<size_t>(1, std::max(nx, ny) / 24);
    double fastest = 0;
    for (size_t k = 0; k < ux.size(); ++k)
      if (std::isfinite(ux[k])) fastest = std::max(fastest, std::hypot(ux[k], uy[k]));
    const double spacing =
        double(stride) * (fields.is_polar() ? axes[1].spacing() : std::min(axes[0].spacing(), axes[1].spacing()));
    Curve vectors;
    vectors.style = CurveStyle::Vectors;
    for (size_t j = stride / 2; j < ny && fastest > 0; j += stride)
      for (size_t i = stride / 2; i < nx; i += stride) {
        const size_t k = i + nx * j;
        if (!std::isfinite(ux[k]) || fields.column("phi").values[k] < 0.5 * fields.settings.dense_phi) continue;
        vectors.x.push_back(node_x[k]);
        vectors.y.push_back(node_y[k]);
        vectors.dx.push_back(ux[k] * 0.9 * spacing / fastest);
        vectors.dy.push_back(uy[k] * 0.9 * spacing / fastest);
      }
    if (!vectors.x.empty()) {
      panel.curves.push_back(vectors);
      caption += "; arrows: velocity, the longest " + number(fastest) + " " + fields.settings.units.velocity();
    }
  }
  Figure figure{"fields_" + column, caption, {}};
  const double aspect = (panel.x_range->second - panel.x_range->first) / (panel.y_range->second - panel.y_range->first);
  const double long_side = 900;
  figure.width_px = static_cast<int>(std::lround((aspect >= 1 ? long_side : long_side * aspect) + 260));
  figure.height_px = static_cast<int>(std::lround(std::max(aspect >= 1 ? long_side / aspect : long_side, 150.0) + 130));
  figure.panels = {panel};
  return figure;
}

Curve profile_curve(const Fields& fields, const std::string& name, const std::string& title)
{
  const auto& coordinate = fields.columns.front().values;
  const auto& values = fields.column(name).values;
  Curve curve;
  curve.title = title;
  curve.style = CurveStyle::Lines;
  for (size_t k = 0; k < values.size(); ++k) {
    curve.x.push_back(std::isfinite(values[k]) ? values[k] : NAN);
    curve.y.push_back(coordinate[k]);
  }
  return curve;
}

// A step of 1, 2 or 5 times a power of ten that cuts the panel's values in at most four intervals:
// tick labels of four narrow panels side by side must not touch.
std::optional<double> four_intervals(const Panel& panel)
{
  double low = INFINITY, high = -INFINITY;
  for (const auto& curve : panel.curves)
    for (double v : curve.x)
      if (std::isfinite(v)) low = std::min(low, v), high = std::max(high, v);
  if (!(high > low)) return std::nullopt;
  const double quarter = (high - low) / 4, decade = std::pow(10.0, std::floor(std::log10(quarter)));
  for (double factor : {1.0, 2.0, 5.0})
    if (factor * decade >= quarter) return factor * decade;
  return 10 * decade;
}

// Panels side by side, the profile's coordinate upwards in each.
Figure profile_figure(const Fields& fields)
{
  const auto& u = fields.settings.units;
  const std::string coordinate = with_unit(fields.columns.front().name, u.length);
  const bool contacts = !fields.settings.contacts_path.empty();
  std::vector<Panel> panels(4);
  panels[0].title = "packing fraction";
  panels[0].x_label = "phi";
  panels[0].curves = {profile_curve(fields, "phi", "phi")};
  panels[1].title = "velocity";
  panels[1].x_label = with_unit("u", u.velocity());
  panels[1].curves = {profile_curve(fields, "ux", "u_x"), profile_curve(fields, "uy", "u_y")};
  panels[2].title = contacts ? "stress (kinetic + contact)" : "stress (kinetic only)";
  panels[2].x_label = with_unit("stress", u.stress);
  panels[2].curves = {profile_curve(fields, "s_xx", "s_xx"), profile_curve(fields, "s_yy", "s_yy"),
                      profile_curve(fields, "s_yx", "s_yx"), profile_curve(fields, "P", "P")};
  panels[3].title = "granular temperature";
  panels[3].x_label = with_unit("T", u.temperature());
  panels[3].curves = {profile_curve(fields, "T", "T")};
  // Curves with no defined point (the velocity where no grain is) are left out, then empty panels.
  std::vector<Panel> drawn;
  for (auto& panel : panels) {
    std::vector<Curve> kept;
    for (auto& curve : panel.curves)
      if (std::any_of(curve.x.begin(), curve.x.end(), [](double v) { return std::isfinite(v); })) kept.push_back(curve);
    panel.curves = kept;
    if (!kept.empty()) drawn.push_back(panel);
  }
  panels = drawn;
  for (size_t p = 0; p < panels.size(); ++p) {
    panels[p].y_label = p == 0 ? coordinate : "";
    panels[p].origin_x = double(p) / double(panels.size());
    panels[p].width = 1.0 / double(panels.size());
    panels[p].key = "top right";
    panels[p].x_tick_step = four_intervals(panels[p]);
    const auto& coordinate_values = fields.columns.front().values;
    panels[p].y_range = std::make_pair(coordinate_values.front(), coordinate_values.back());
  }
  Figure figure{"fields_profile", "Profiles along " + fields.columns.front().name + "; " + averaging(fields), panels};
  figure.width_px = 1400;
  figure.height_px = 650;
  return figure;
}

Figure flow_rule_figure(const Fields& fields)
{
  const auto& mu = fields.column("mu").values;
  const auto& inertial = fields.column("I").values;
  const auto& phi = fields.column("phi").values;
  Curve mu_points, phi_points;
  for (size_t k = 0; k < mu.size(); ++k) {
    if (!(phi[k] >= fields.settings.dense_phi) || !(inertial[k] > 0) || !std::isfinite(mu[k])) continue;
    mu_points.x.push_back(inertial[k]);
    mu_points.y.push_back(mu[k]);
    phi_points.x.push_back(inertial[k]);
    phi_points.y.push_back(phi[k]);
  }
  const std::string nodes = "nodes with phi >= " + number(fields.settings.dense_phi);
  mu_points.title = phi_points.title = nodes;
  mu_points.style = phi_points.style = CurveStyle::Points;
  std::vector<Panel> panels(2);
  panels[0].title = "mu(I)";
  panels[0].y_label = "mu = tau / P";
  panels[0].curves = {mu_points};
  panels[1].title = "phi(I)";
  panels[1].y_label = "phi";
  panels[1].curves = {phi_points};
  for (size_t p = 0; p < 2; ++p) {
    panels[p].x_label =
        "I = gamma_dot d / sqrt(P / rho_s), d = " + number(fields.diameter) + " " + fields.settings.units.length;
    panels[p].log_x = !mu_points.x.empty();
    panels[p].origin_x = 0.5 * double(p);
    panels[p].width = 0.5;
    panels[p].key = "top left";
  }
  return {"fields_mu_I", "mu(I) and phi(I) of the " + nodes + "; " + averaging(fields), panels, 1300, 600};
}

}  // namespace

std::vector<Figure> field_figures(const Fields& fields)
{
  std::vector<Figure> figures;
  if (fields.is_profile()) {
    figures.push_back(profile_figure(fields));
  } else {
    figures.push_back(map_figure(fields, "phi", "Packing fraction and velocity", true));
    figures.push_back(map_figure(fields, "P", "Pressure", true));
    figures.push_back(map_figure(fields, "mu", "Friction tau / P", false));
  }
  auto flow_rule = flow_rule_figure(fields);
  if (!flow_rule.panels[0].curves[0].x.empty()) figures.push_back(flow_rule);
  return figures;
}

}  // namespace cdpost
