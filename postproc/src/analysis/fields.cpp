#include "analysis/fields.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "io/ave_time.h"
#include "io/dump.h"
#include "io/progress.h"
#include "io/tokens.h"
#include "output/results.h"
#include "signal/statistics.h"

namespace cdpost {

namespace {

const double nan = std::numeric_limits<double>::quiet_NaN();

// What each grain spreads around its centre, and each contact along its branch vector.
enum GrainSum { kMass, kArea, kMomentumX, kMomentumY, kMvxx, kMvyy, kMvxy, kGrainSums };
enum ContactSum { kLxFx, kLyFy, kLxFy, kLyFx, kContactSums };

struct AtomColumns {
  size_t id, x, y, vx, vy, radius;
  std::optional<size_t> mass;
};

AtomColumns atom_columns(const DumpFrame& frame)
{
  AtomColumns c{frame.column_index("id"),
                frame.column_index("x"),
                frame.column_index("y"),
                frame.column_index("vx"),
                frame.column_index("vy"),
                frame.column_index("radius"),
                std::nullopt};
  const auto mass = std::find(frame.columns.begin(), frame.columns.end(), "mass");
  if (mass != frame.columns.end()) c.mass = static_cast<size_t>(mass - frame.columns.begin());
  return c;
}

// The fix's local array (doc/fix_contact_dynamics.rst): first and second atom IDs, wall number,
// p_n, p_t, contact point x and y, dumped as PREFIX[1] ... PREFIX[7] (f_cd[1] for fix cd).
struct ContactColumns {
  size_t first, second, wall, impulse_n, impulse_t, point_x, point_y;
};

ContactColumns contact_columns(const DumpFrame& frame)
{
  for (const auto& name : frame.columns) {
    if (name.size() < 4 || name.compare(name.size() - 3, 3, "[1]") != 0) continue;
    const std::string prefix = name.substr(0, name.size() - 3);
    std::array<size_t, 7> index{};
    bool all = true;
    for (size_t k = 0; k < 7 && all; ++k) {
      const auto found =
          std::find(frame.columns.begin(), frame.columns.end(), prefix + "[" + std::to_string(k + 1) + "]");
      all = found != frame.columns.end();
      if (all) index[k] = static_cast<size_t>(found - frame.columns.begin());
    }
    if (all) return {index[0], index[1], index[2], index[3], index[4], index[5], index[6]};
  }
  throw InputError(frame.source, frame.line,
                   "no columns of the fix's local array (NAME[1] to NAME[7], e.g. f_cd[1] ... f_cd[7] for fix cd; "
                   "columns: " +
                       join_names(frame.columns) + ")");
}

// The frame's box: the shortest displacement between two points, across periodic sides.
struct Box {
  std::array<double, 2> length;
  std::array<bool, 2> periodic;
  double tilt = 0;  // a triclinic box's xy: the image across y is shifted by it along x
  std::array<double, 2> displacement(double ax, double ay, double bx, double by) const
  {
    std::array<double, 2> d{bx - ax, by - ay};
    if (periodic[1]) {
      const double images = std::round(d[1] / length[1]);
      d[1] -= images * length[1];
      d[0] -= images * tilt;
    }
    if (periodic[0]) d[0] -= length[0] * std::round(d[0] / length[0]);
    return d;
  }
};

std::optional<double> frame_time(const DumpFrame& frame, const FieldsSettings& settings)
{
  if (frame.time) return frame.time;
  if (settings.timestep_size) return double(frame.timestep) * *settings.timestep_size;
  return std::nullopt;
}

// The streamed dumps, the window and the sums on the grid.
class FieldAccumulator {
 public:
  explicit FieldAccumulator(const FieldsSettings& settings) : settings_(settings) {}

  void set_up(const DumpFrame& first, Fields& fields)
  {
    columns_ = atom_columns(first);
    if (!columns_.mass && !settings_.grain_density)
      throw InputError(first.source, first.line,
                       "no 'mass' column: give --density, the grains' density (masses pi r^2 rho)");
    const auto periodic = periodic_xy(first, settings_.periodic);
    const int dims = settings_.along < 0 ? 2 : 1;
    const Kernel kernel(settings_.kernel, settings_.width, dims);
    fields.kernel_description = kernel.describe(settings_.units.length);
    GridAxis x{first.xlo, first.xhi, 1, periodic[0]}, y{first.ylo, first.yhi, 1, periodic[1]};
    if (settings_.x_range) x = {(*settings_.x_range)[0], (*settings_.x_range)[1], 1, false};
    if (settings_.range) y = {(*settings_.range)[0], (*settings_.range)[1], 1, false};
    if (settings_.along == 0 && settings_.range) x = {(*settings_.range)[0], (*settings_.range)[1], 1, false};
    const std::array<double, 2> box_length{first.xhi - first.xlo, first.yhi - first.ylo};
    // Each node must see one image of a grain, and of a branch vector (at most a diameter long).
    double largest_radius = 0;
    for (size_t atom = 0; atom < first.atoms; ++atom)
      largest_radius = std::max(largest_radius, first.value(atom, columns_.radius));
    for (int k = 0; k < 2; ++k)
      if (periodic[k] && box_length[k] < 2 * kernel.range() + 2 * largest_radius)
        throw AnalysisError(std::string("the box is ") + (k ? "y" : "x") +
                            "-periodic but too short for the kernel: its range is " + std::to_string(kernel.range()) +
                            ", give a smaller --width");
    auto cells_for = [&](const GridAxis& axis, size_t given, double spacing) {
      return given ? given : std::max<size_t>(1, static_cast<size_t>(std::ceil(axis.length() / spacing)));
    };
    if (settings_.polar) {
      const PolarCells& c = *settings_.polar;
      const GridAxis angle{0, 2 * M_PI, c.sectors, true}, radius{c.r_in, c.r_out, c.rings, false};
      std::vector<std::array<double, 2>> nodes;
      for (size_t i = 0; i < c.rings; ++i)
        for (size_t j = 0; j < c.sectors; ++j)
          nodes.push_back({c.centre_x + radius.node(i) * std::cos(angle.node(j)),
                           c.centre_y + radius.node(i) * std::sin(angle.node(j))});
      grains_.emplace(kernel, nodes, kGrainSums);
      contacts_.emplace(kernel, nodes, kContactSums);
      fields.axes = {angle, radius};
    } else if (settings_.along < 0) {
      x.cells = cells_for(x, settings_.cells[0], settings_.width);
      y.cells = cells_for(y, settings_.cells[1], settings_.width);
      grains_.emplace(kernel, x, y, kGrainSums);
      contacts_.emplace(kernel, x, y, kContactSums);
      fields.axes = {x, y};
    } else {
      GridAxis along = settings_.along == 0 ? x : y;
      along.cells = cells_for(along, settings_.cells[0], 0.5 * settings_.width);
      // A sheared box's images across y move at image_velocity: spread them explicitly, unwrapped.
      sheared_ = settings_.image_velocity && settings_.along == 1 && periodic[1];
      if (sheared_) along.periodic = false, image_low_ = first.ylo, image_high_ = first.yhi, reach_ = kernel.range();
      const double across = settings_.along == 0 ? box_length[1] : box_length[0];
      grains_.emplace(kernel, settings_.along, along, across, kGrainSums);
      contacts_.emplace(kernel, settings_.along, along, across, kContactSums);
      fields.axes = {along, GridAxis{}};
    }
    box_.periodic = periodic;
    fields.diameter = settings_.diameter ? *settings_.diameter : mean_diameter(first, columns_.radius);
    fields.diameter_source = settings_.diameter ? "given" : "the first frame's mean diameter";
  }

  void add_grains(const DumpFrame& frame)
  {
    box_.length = {frame.xhi - frame.xlo, frame.yhi - frame.ylo};
    box_.tilt = frame.xy;
    tilted_ = tilted_ || frame.xy != 0;
    if (frame.xy != 0 && settings_.along != 1)
      throw InputError(frame.source, frame.line,
                       "a tilted (triclinic) box: only a profile along y (--along y) is coarse-grained in it");
    index_.clear();
    for (size_t atom = 0; atom < frame.atoms; ++atom) {
      index_[static_cast<long>(frame.value(atom, columns_.id))] = atom;
      const double r = frame.value(atom, columns_.radius);
      const double m = columns_.mass ? frame.value(atom, *columns_.mass) : M_PI * r * r * *settings_.grain_density;
      const double x = frame.value(atom, columns_.x), y = frame.value(atom, columns_.y);
      const double vx = frame.value(atom, columns_.vx), vy = frame.value(atom, columns_.vy);
      for (int image : images(y, y)) {
        const double ux = vx + image * settings_.image_velocity.value_or(0.0);
        const double weights[kGrainSums] = {m, M_PI * r * r, m * ux, m * vy, m * ux * ux, m * vy * vy, m * ux * vy};
        grains_->add_point({x, y + image * box_.length[1]}, weights);
      }
    }
  }

  // The images across y (-1, 0, +1) of something spanning [low, high] in y that a sheared box's
  // unwrapped profile must receive; just itself otherwise.
  std::vector<int> images(double low, double high) const
  {
    if (!sheared_) return {0};
    std::vector<int> found{0};
    if (low - reach_ < image_low_) found.push_back(1);     // seen from above the top, one box up
    if (high + reach_ > image_high_) found.push_back(-1);  // seen from below the floor
    return found;
  }

  // The contacts of the atoms' frame: each force f = p / dt on the first body, spread along the
  // branch vector l from the second body's centre (the contact point for a wall) to the first's,
  // all at the step's predicted configuration x_m, where the fix solved them (its normal is l's):
  // taken at the step's end instead, a sheared pair's normal has turned by theta dt times its
  // rotation rate, and the shear stress with it.
  void add_contacts(const DumpFrame& atoms, const DumpFrame& frame, double dt, const ContactColumns& c)
  {
    const double back = settings_.theta * dt;  // x_m = x - theta dt v
    Box predicted = box_;                      // a deforming box's tilt at x_m
    if (settings_.image_velocity) predicted.tilt -= back * *settings_.image_velocity;
    auto at_predicted = [&](size_t atom) {
      return std::array<double, 2>{atoms.value(atom, columns_.x) - back * atoms.value(atom, columns_.vx),
                                   atoms.value(atom, columns_.y) - back * atoms.value(atom, columns_.vy)};
    };
    double weights[kContactSums];
    auto atom_of = [&](double id, size_t row) {
      const auto found = index_.find(static_cast<long>(id));
      if (found == index_.end())
        throw InputError(frame.source, frame.line,
                         "contact " + std::to_string(row + 1) + " names atom " + std::to_string(long(id)) +
                             ", absent from " + atoms.source + " at timestep " + std::to_string(atoms.timestep));
      return found->second;
    };
    for (size_t row = 0; row < frame.atoms; ++row) {
      const auto [ax, ay] = at_predicted(atom_of(frame.value(row, c.first), row));
      const auto [bx, by] = frame.value(row, c.second) != 0
                                ? at_predicted(atom_of(frame.value(row, c.second), row))
                                : std::array<double, 2>{frame.value(row, c.point_x), frame.value(row, c.point_y)};
      const auto l = predicted.displacement(bx, by, ax, ay);  // from b to a
      const double length = std::hypot(l[0], l[1]);
      if (!(length > 0)) continue;
      const double nx = l[0] / length, ny = l[1] / length;
      const double pn = frame.value(row, c.impulse_n), pt = frame.value(row, c.impulse_t);
      const double fx = (pn * nx - pt * ny) / dt, fy = (pn * ny + pt * nx) / dt;
      weights[kLxFx] = l[0] * fx;
      weights[kLyFy] = l[1] * fy;
      weights[kLxFy] = l[0] * fy;
      weights[kLyFx] = l[1] * fx;
      for (int image : images(std::min(ay, ay - l[1]), std::max(ay, ay - l[1])))
        contacts_->add_segment({ax - l[0], ay - l[1] + image * box_.length[1]}, l, weights);
    }
    contacts_added_ += frame.atoms;
  }

  const KernelGrid& grains() const { return *grains_; }
  const KernelGrid& contacts() const { return *contacts_; }
  size_t contacts_added() const { return contacts_added_; }
  bool tilted() const { return tilted_; }

 private:
  const FieldsSettings& settings_;
  AtomColumns columns_{};
  Box box_{};
  std::optional<KernelGrid> grains_, contacts_;
  std::unordered_map<long, size_t> index_;
  bool tilted_ = false;   // a frame's box was tilted
  bool sheared_ = false;  // a profile along y of a box whose images across y move (image_velocity)
  double image_low_ = 0, image_high_ = 0, reach_ = 0;
  size_t contacts_added_ = 0;
};

// The derivative of `u` along grid axis `k` at every node (central differences, one-sided at a
// closed end, NaN beside an undefined value).
std::vector<double> derivative(const std::vector<double>& u, const std::array<GridAxis, 2>& axes, bool profile, int k)
{
  const size_t nx = axes[0].cells, ny = profile ? 1 : axes[1].cells;
  const GridAxis& axis = axes[k];
  const long n = static_cast<long>(axis.cells);
  std::vector<double> du(u.size(), nan);
  for (size_t j = 0; j < ny; ++j)
    for (size_t i = 0; i < nx; ++i) {
      const long at = static_cast<long>(k == 0 ? i : j);
      auto node = [&](long m) { return k == 0 ? size_t(m) + nx * j : i + nx * size_t(m); };
      long lo = at - 1, hi = at + 1;
      if (axis.periodic) lo = (lo + n) % n, hi = hi % n;
      else lo = std::max(0L, lo), hi = std::min(n - 1, hi);
      if (lo == hi) continue;
      const double steps = axis.periodic ? 2.0 : double(hi - lo);
      du[node(at)] = (u[node(hi)] - u[node(lo)]) / (steps * axis.spacing());
    }
  return du;
}

// Polar cells: r and theta of each node, the velocity and the stress in the frame (e_r, e_theta).
void add_polar_components(Fields& fields)
{
  const size_t n = fields.columns.front().values.size(), sectors = fields.axes[0].cells;
  const FieldUnits& u = fields.settings.units;
  std::vector<double> r(n), theta(n), ur(n, nan), ut(n, nan), srr(n, nan), stt(n, nan), srt(n, nan), str(n, nan);
  const auto& ux = fields.column("ux").values;
  const auto& uy = fields.column("uy").values;
  const auto& sxx = fields.column("s_xx").values;
  const auto& syy = fields.column("s_yy").values;
  const auto& sxy = fields.column("s_xy").values;
  const auto& syx = fields.column("s_yx").values;
  for (size_t k = 0; k < n; ++k) {
    r[k] = fields.axes[1].node(k / sectors), theta[k] = fields.axes[0].node(k % sectors);
    const double cs = std::cos(theta[k]), sn = std::sin(theta[k]);
    ur[k] = cs * ux[k] + sn * uy[k];
    ut[k] = -sn * ux[k] + cs * uy[k];
    srr[k] = cs * cs * sxx[k] + sn * sn * syy[k] + cs * sn * (sxy[k] + syx[k]);
    stt[k] = sn * sn * sxx[k] + cs * cs * syy[k] - cs * sn * (sxy[k] + syx[k]);
    srt[k] = cs * sn * (syy[k] - sxx[k]) + cs * cs * sxy[k] - sn * sn * syx[k];
    str[k] = cs * sn * (syy[k] - sxx[k]) - sn * sn * sxy[k] + cs * cs * syx[k];
  }
  fields.columns.push_back({"r", u.length, "node's distance from the polar centre", r});
  fields.columns.push_back({"theta", "rad", "node's angle from +x, counter-clockwise", theta});
  fields.columns.push_back({"u_r", u.velocity(), "radial velocity", ur});
  fields.columns.push_back({"u_theta", u.velocity(), "azimuthal velocity", ut});
  fields.columns.push_back({"s_rr", u.stress, "stress rr", srr});
  fields.columns.push_back({"s_tt", u.stress, "stress theta theta", stt});
  fields.columns.push_back({"s_rt", u.stress, "stress r theta: force along e_theta across planes normal to e_r", srt});
  fields.columns.push_back({"s_tr", u.stress, "stress theta r", str});
}

void derive(Fields& fields, const FieldAccumulator& sums)
{
  const KernelGrid& g = sums.grains();
  const KernelGrid& c = sums.contacts();
  const double frames = double(fields.frames);
  const size_t n = g.nodes();
  const FieldUnits& u = fields.settings.units;
  const bool with_contacts = !fields.settings.contacts_path.empty();
  auto column = [&](const std::string& name, const std::string& unit, const std::string& description) {
    fields.columns.push_back({name, unit, description, std::vector<double>(n, nan)});
    return &fields.columns.back().values;
  };
  fields.columns.reserve(48);  // the references below stay valid
  if (fields.is_profile()) {
    auto& z = *column(fields.settings.along == 0 ? "x" : "y", u.length, "node coordinate");
    for (size_t k = 0; k < n; ++k) z[k] = g.position(k)[0];
  } else {
    auto& x = *column("x", u.length, "node x");
    auto& y = *column("y", u.length, "node y");
    for (size_t k = 0; k < n; ++k) x[k] = g.position(k)[0], y[k] = g.position(k)[1];
  }
  auto& phi = *column("phi", "", "packing fraction: sum of pi r^2 psi");
  auto& rho = *column("rho", u.density, "mass density: sum of m psi");
  auto& ux = *column("ux", u.velocity(), "velocity x: momentum density / rho");
  auto& uy = *column("uy", u.velocity(), "velocity y");
  auto& temperature = *column("T", u.temperature(), "granular temperature (sk_xx + sk_yy) / (2 rho)");
  auto& kxx = *column("sk_xx", u.stress, "kinetic stress: sum of m v'v' psi, v' = v - u");
  auto& kyy = *column("sk_yy", u.stress, "kinetic stress yy");
  auto& kxy = *column("sk_xy", u.stress, "kinetic stress xy (= yx)");
  std::vector<double> zero(n, 0.0);
  std::vector<double>*cxx = &zero, *cyy = &zero, *cxy = &zero, *cyx = &zero;
  if (with_contacts) {
    cxx = column("sc_xx", u.stress, "contact stress: sum of l_a f_b along the branch, compression > 0");
    cyy = column("sc_yy", u.stress, "contact stress yy");
    cxy = column("sc_xy", u.stress, "contact stress xy: l_x f_y (force along y across planes normal to x)");
    cyx = column("sc_yx", u.stress, "contact stress yx: l_y f_x (force along x across planes normal to y)");
    for (size_t k = 0; k < n; ++k) {
      (*cxx)[k] = c.value(k, kLxFx) / frames;
      (*cyy)[k] = c.value(k, kLyFy) / frames;
      (*cxy)[k] = c.value(k, kLxFy) / frames;
      (*cyx)[k] = c.value(k, kLyFx) / frames;
    }
  }
  double densest = 0;
  for (size_t k = 0; k < n; ++k) densest = std::max(densest, g.value(k, kMass));
  for (size_t k = 0; k < n; ++k) {
    phi[k] = g.value(k, kArea) / frames;
    rho[k] = g.value(k, kMass) / frames;
    kxx[k] = kyy[k] = kxy[k] = 0;
    if (!(g.value(k, kMass) > 1e-9 * densest)) continue;  // no grain near the node: no velocity
    ux[k] = g.value(k, kMomentumX) / g.value(k, kMass);
    uy[k] = g.value(k, kMomentumY) / g.value(k, kMass);
    kxx[k] = g.value(k, kMvxx) / frames - rho[k] * ux[k] * ux[k];
    kyy[k] = g.value(k, kMvyy) / frames - rho[k] * uy[k] * uy[k];
    kxy[k] = g.value(k, kMvxy) / frames - rho[k] * ux[k] * uy[k];
    temperature[k] = (kxx[k] + kyy[k]) / (2 * rho[k]);
  }
  const std::string total = with_contacts ? "kinetic + contact" : "kinetic only (no contact dump)";
  auto& sxx = *column("s_xx", u.stress, "stress xx, " + total);
  auto& syy = *column("s_yy", u.stress, "stress yy, " + total);
  auto& sxy = *column("s_xy", u.stress, "stress xy, " + total);
  auto& syx = *column("s_yx", u.stress, "stress yx, " + total);
  auto& pressure = *column("P", u.stress, "pressure (s_xx + s_yy) / 2");
  auto& shear = *column("tau", u.stress, "shear stress: norm of the deviator, sqrt(((s_xx - s_yy)/2)^2 + s_sym_xy^2)");
  auto& friction = *column("mu", "", "tau / P");
  auto& rate =
      *column("gamma_dot", u.rate(), "shear rate: 2 x norm of the strain rate's deviator (|du_x/dy| in simple shear)");
  auto& inertial = *column("I", "", "inertial number gamma_dot d / sqrt(P / rho_s), rho_s = rho / phi");
  const bool profile = fields.is_profile();
  const int along = fields.settings.along;
  // Gradients: a profile varies along its axis only.
  std::vector<double> dux_dx(n, 0.0), dux_dy(n, 0.0), duy_dx(n, 0.0), duy_dy(n, 0.0);
  if (fields.is_polar()) {
    // d/dx = cos d/dr - sin / r d/dtheta, d/dy = sin d/dr + cos / r d/dtheta.
    const auto dux_dt = derivative(ux, fields.axes, false, 0), dux_dr = derivative(ux, fields.axes, false, 1);
    const auto duy_dt = derivative(uy, fields.axes, false, 0), duy_dr = derivative(uy, fields.axes, false, 1);
    const size_t sectors = fields.axes[0].cells;
    for (size_t k = 0; k < n; ++k) {
      const double r = fields.axes[1].node(k / sectors), theta = fields.axes[0].node(k % sectors);
      const double cs = std::cos(theta), sn = std::sin(theta);
      dux_dx[k] = cs * dux_dr[k] - sn / r * dux_dt[k], dux_dy[k] = sn * dux_dr[k] + cs / r * dux_dt[k];
      duy_dx[k] = cs * duy_dr[k] - sn / r * duy_dt[k], duy_dy[k] = sn * duy_dr[k] + cs / r * duy_dt[k];
    }
  } else if (!profile) {
    dux_dx = derivative(ux, fields.axes, false, 0), dux_dy = derivative(ux, fields.axes, false, 1);
    duy_dx = derivative(uy, fields.axes, false, 0), duy_dy = derivative(uy, fields.axes, false, 1);
  } else if (along == 1) {
    dux_dy = derivative(ux, fields.axes, true, 0), duy_dy = derivative(uy, fields.axes, true, 0);
  } else {
    dux_dx = derivative(ux, fields.axes, true, 0), duy_dx = derivative(uy, fields.axes, true, 0);
  }
  for (size_t k = 0; k < n; ++k) {
    sxx[k] = kxx[k] + (*cxx)[k];
    syy[k] = kyy[k] + (*cyy)[k];
    sxy[k] = kxy[k] + (*cxy)[k];
    syx[k] = kxy[k] + (*cyx)[k];
    pressure[k] = 0.5 * (sxx[k] + syy[k]);
    shear[k] = std::hypot(0.5 * (sxx[k] - syy[k]), 0.5 * (sxy[k] + syx[k]));
    if (pressure[k] > 0) friction[k] = shear[k] / pressure[k];
    rate[k] = std::hypot(dux_dx[k] - duy_dy[k], dux_dy[k] + duy_dx[k]);
    if (pressure[k] > 0 && phi[k] > 0 && !std::isnan(rate[k]))
      inertial[k] = rate[k] * fields.diameter / std::sqrt(pressure[k] / (rho[k] / phi[k]));
  }
  if (fields.is_polar()) add_polar_components(fields);
}

}  // namespace

FieldUnits FieldUnits::si(const std::string& source)
{
  FieldUnits u;
  u.source = source;
  return u;
}

FieldUnits FieldUnits::lj(const std::string& source)
{
  FieldUnits u;
  u.system = "lj";
  u.length = "sigma";
  u.time = "tau";
  u.mass = "m";
  u.density = "m/sigma^3";
  u.stress = "m/(sigma tau^2)";
  u.source = source;
  return u;
}

std::string FieldUnits::describe() const
{
  const std::string names = system == "si" ? "SI: lengths m, times s, masses kg per m of depth, stress Pa"
                                           : "LJ: lengths sigma, times tau, masses m per sigma of depth, stress "
                                             "m/(sigma tau^2)";
  return names + " (" + source + ")";
}

const FieldColumn& Fields::column(const std::string& name) const
{
  for (const auto& c : columns)
    if (c.name == name) return c;
  throw AnalysisError("no field column '" + name + "'");
}

Fields compute_fields(const FieldsSettings& settings)
{
  if (!(settings.width > 0)) throw AnalysisError("the kernel width must be positive");
  Fields fields;
  fields.settings = settings;
  DumpReader atoms(settings.dump_path);
  std::optional<DumpReader> contacts;
  DumpFrame frame, contact_frame;
  bool contact_frame_read = false;
  std::optional<ContactColumns> contact_columns_found;
  if (!settings.contacts_path.empty()) {
    if (!settings.timestep_size)
      throw AnalysisError(
          "the contact forces are impulses / dt: give --dt, the run's time step (or a chute.params "
          "with dt_s beside the dump)");
    contacts.emplace(settings.contacts_path);
    contact_frame_read = contacts->next(contact_frame);
  }
  const bool windowed = settings.t_start || settings.t_end;
  FieldAccumulator sums(settings);
  Progress progress("reading " + settings.dump_path, true, settings.progress);
  double contact_rows = 0;
  long widest_gap = 0;  // steps between frames used
  while (atoms.next(frame)) {
    progress.update(atoms.source().fraction_read(), "timestep " + std::to_string(frame.timestep));
    const auto time = frame_time(frame, settings);
    if (windowed && !time)
      throw InputError(
          frame.source, frame.line,
          "no 'ITEM: TIME' in the frame and no --dt: the window --t-start/--t-end needs the frames' times");
    if (settings.t_start && *time < *settings.t_start - 1e-12 * std::abs(*settings.t_start)) continue;
    if (settings.t_end && *time > *settings.t_end + 1e-12 * std::abs(*settings.t_end)) break;
    if (contacts) {
      while (contact_frame_read && contact_frame.timestep < frame.timestep)
        contact_frame_read = contacts->next(contact_frame);
      if (!contact_frame_read || contact_frame.timestep != frame.timestep) {
        ++fields.frames_skipped_no_contacts;
        continue;
      }
    }
    if (fields.frames == 0) {
      sums.set_up(frame, fields);
      fields.first_step = frame.timestep;
      fields.first_time = time;
    }
    sums.add_grains(frame);
    if (contacts) {
      if (!contact_columns_found && contact_frame.atoms > 0) contact_columns_found = contact_columns(contact_frame);
      if (contact_frame.atoms > 0)
        sums.add_contacts(frame, contact_frame, *settings.timestep_size, *contact_columns_found);
      contact_rows += double(contact_frame.atoms);
    }
    if (fields.frames > 0) widest_gap = std::max(widest_gap, frame.timestep - fields.last_step);
    fields.last_step = frame.timestep;
    fields.last_time = time;
    ++fields.frames;
  }
  if (fields.frames == 0)
    throw AnalysisError(settings.dump_path + ": no frame" + (windowed ? " in the window" : std::string()) +
                        (contacts ? " with a frame of the same timestep in " + settings.contacts_path : std::string()));
  if (fields.frames_skipped_no_contacts > 0)
    fields.warnings.push_back(std::to_string(fields.frames_skipped_no_contacts) + " frames of " + settings.dump_path +
                              " have no frame of the same timestep in " + settings.contacts_path + ": not used");
  if (contacts && widest_gap > 1)
    fields.warnings.push_back("frames up to " + std::to_string(widest_gap) +
                              " steps apart: a rigid contact's impulse comes in bursts, and the contact stress of "
                              "frames apart scatters; dump the contacts every step for a stress to the percent "
                              "(doc/fields.md)");
  if (sums.tilted() && !settings.image_velocity)
    fields.warnings.push_back(
        "a tilted box: if fix deform shears it, give --image-velocity (its tilt's rate), or the "
        "velocity and kinetic stress near the y boundary mix the images' streaming");
  fields.mean_contacts = contact_rows / double(fields.frames);
  derive(fields, sums);
  return fields;
}

namespace {

std::string json_text(const std::string& text)
{
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

std::string json_number(double value)
{
  if (!std::isfinite(value)) return "null";
  std::ostringstream text;
  text.precision(9);
  text << value;
  return text.str();
}

std::string header_name(const FieldColumn& c)
{
  return c.unit.empty() ? c.name : c.name + "_" + c.unit;
}

}  // namespace

void write_fields_tables(const Fields& fields, const std::string& directory)
{
  std::filesystem::create_directories(directory);
  {
    auto out = open_output(directory + "/fields.csv");
    out << "# cdpost fields: " << fields.kernel_description << "; units " << fields.settings.units.describe() << "; "
        << fields.frames << " frames, timesteps " << fields.first_step << " to " << fields.last_step << "\n";
    for (size_t c = 0; c < fields.columns.size(); ++c) out << (c ? "," : "") << header_name(fields.columns[c]);
    out << "\n";
    out.precision(9);
    const size_t n = fields.columns.front().values.size();
    for (size_t k = 0; k < n; ++k) {
      for (size_t c = 0; c < fields.columns.size(); ++c) {
        if (c) out << ',';
        const double v = fields.columns[c].values[k];
        if (std::isfinite(v)) out << v;
      }
      out << "\n";
    }
  }
  auto out = open_output(directory + "/fields.json");
  const auto& s = fields.settings;
  out << "{\n  \"command\": \"cdpost fields\",\n  \"dump\": " << json_text(s.dump_path)
      << ",\n  \"contacts\": " << (s.contacts_path.empty() ? "null" : json_text(s.contacts_path))
      << ",\n  \"units\": " << json_text(s.units.describe()) << ",\n  \"length_unit\": " << json_text(s.units.length)
      << ",\n  \"time_unit\": " << json_text(s.units.time) << ",\n  \"stress_unit\": " << json_text(s.units.stress)
      << ",\n  \"kernel\": " << json_text(fields.kernel_description) << ",\n  \"geometry\": "
      << json_text(s.polar        ? "polar cells"
                   : s.along < 0  ? "map"
                   : s.along == 0 ? "profile along x"
                                  : "profile along y")
      << ",\n  \"frames\": " << fields.frames << ",\n  \"first_timestep\": " << fields.first_step
      << ",\n  \"last_timestep\": " << fields.last_step
      << ",\n  \"first_time\": " << (fields.first_time ? json_number(*fields.first_time) : "null")
      << ",\n  \"last_time\": " << (fields.last_time ? json_number(*fields.last_time) : "null")
      << ",\n  \"contacts_per_frame\": " << json_number(fields.mean_contacts)
      << ",\n  \"d\": " << json_number(fields.diameter) << ",\n  \"d_source\": " << json_text(fields.diameter_source)
      << ",\n  \"warnings\": [";
  for (size_t w = 0; w < fields.warnings.size(); ++w) out << (w ? ", " : "") << json_text(fields.warnings[w]);
  out << "],\n  \"columns\": [\n";
  for (size_t c = 0; c < fields.columns.size(); ++c) {
    const auto& col = fields.columns[c];
    out << "    {\"name\": " << json_text(col.name) << ", \"unit\": " << json_text(col.unit)
        << ", \"description\": " << json_text(col.description) << ", \"values\": [";
    for (size_t k = 0; k < col.values.size(); ++k) out << (k ? ", " : "") << json_number(col.values[k]);
    out << "]}" << (c + 1 < fields.columns.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

}  // namespace cdpost
