// Coarse-grained continuum fields of a 2D dump (Weinhart et al. 2012, Goldhirsch 2010): packing
// fraction, density, velocity, granular temperature, kinetic and contact stress on a map or a
// profile, averaged over a time window; derived pressure, shear stress, friction, shear rate and
// inertial number. The dumps are streamed a frame at a time (doc/fields.md).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "signal/coarse_graining.h"

namespace cdpost {

// The units the dump is written in, named in every output. Masses are per unit depth (LAMMPS's
// 2D disks: m = pi r^2 rho), so a 2D stress is a 3D one: Pa in SI.
struct FieldUnits {
  std::string system = "si";  // si | lj
  std::string length = "m", time = "s", mass = "kg", density = "kg/m^3", stress = "Pa";
  std::string source;  // where the choice came from
  static FieldUnits si(const std::string& source);
  static FieldUnits lj(const std::string& source);
  std::string velocity() const { return length + "/" + time; }
  std::string rate() const { return "1/" + time; }
  std::string temperature() const { return length + "^2/" + time + "^2"; }
  std::string describe() const;  // "SI: m, s, kg per unit depth, stress Pa (from ...)"
};

// Polar cells about a drum's axis: `rings` x `sectors` nodes at the cells' centres between radii
// r_in and r_out (input length units), the angle from +x counter-clockwise.
struct PolarCells {
  double centre_x = 0, centre_y = 0, r_in = 0, r_out = 0;
  size_t rings = 0, sectors = 0;
};

struct FieldsSettings {
  std::string dump_path;      // dump custom: id x y vx vy radius [mass]
  std::string contacts_path;  // dump local of the fix's local array; empty: no contact stress
  FieldUnits units;
  KernelShape kernel = KernelShape::gaussian;
  double width = 0;                            // kernel standard deviation, input length units
  int along = -1;                              // -1: a map; 0 or 1: a profile along x or y, averaged over the other
  std::optional<PolarCells> polar;             // instead of a map: polar cells (along must be -1)
  std::array<size_t, 2> cells = {0, 0};        // map cells along x, y (a profile: cells[0] along its axis)
  std::optional<std::array<double, 2>> range;  // the profile's or the map's y extent; default the box
  std::optional<std::array<double, 2>> x_range;
  std::optional<std::array<bool, 2>> periodic;  // default: the dump's box flags
  std::optional<double> t_start, t_end;         // window, input time units
  std::optional<double> timestep_size;          // dt: time = step dt, force = impulse / dt
  std::optional<double> grain_density;          // masses pi r^2 rho when the dump has no mass column
  std::optional<double> diameter;               // d of I; default the first frame's mean diameter
  // A sheared periodic box (fix deform xy, remap v): the image across y moves along x at this
  // velocity (the tilt's rate, rate x ly); a profile along y then receives the images' velocities.
  std::optional<double> image_velocity;
  // The fix's Moreau-Jean theta: a step's contacts act at its predicted configuration
  // x_m = x - theta dt v (x, v the dumped end of the step), where their branch vectors are taken.
  double theta = 0.5;
  double dense_phi = 0.5;  // mu(I), phi(I): only nodes this dense
  bool progress = false;
};

// One output column: name (with unit in the tables), unit, meaning, a value per node (NaN where
// undefined: no grain near the node, or no pressure).
struct FieldColumn {
  std::string name, unit, description;
  std::vector<double> values;
};

struct Fields {
  FieldsSettings settings;
  std::string kernel_description;
  double diameter = 0;  // d of I, input length units
  std::string diameter_source;
  std::array<GridAxis, 2> axes;  // a profile uses axes[0]; polar cells: angle, radius
  size_t frames = 0, frames_skipped_no_contacts = 0;
  long first_step = 0, last_step = 0;
  std::optional<double> first_time, last_time;
  double mean_contacts = 0;          // contacts a frame
  std::vector<FieldColumn> columns;  // coordinates first
  std::vector<std::string> warnings;
  const FieldColumn& column(const std::string& name) const;
  bool is_profile() const { return settings.along >= 0; }
  bool is_polar() const { return settings.polar.has_value(); }
};

// Reads the dumps frame by frame and averages the fields over the frames in the window.
// InputError for a bad or truncated dump (its file and line), AnalysisError when no frame is used.
Fields compute_fields(const FieldsSettings& settings);

// Writes DIR/fields.csv (one row a node, units in the names, empty where undefined) and
// DIR/fields.json (the settings, units and columns).
void write_fields_tables(const Fields& fields, const std::string& directory);

}  // namespace cdpost
