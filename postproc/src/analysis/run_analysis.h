// The analysis of one chute run: from the files a deck writes to every measured number of
// doc/scene.md (stationary window, U, phi, h, u(z) fits, spectra of v(t), shear rate, I).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/along_cell.h"
#include "analysis/solver_health.h"
#include "fit/creep.h"
#include "fit/packing_profile.h"
#include "fit/profile_fits.h"
#include "output/results.h"
#include "signal/spectrum.h"
#include "signal/stationary.h"

namespace cdpost {

// Physical scales and the units of the input files. Internally everything is SI; results
// are reported in d, sqrt(d/g), sqrt(g d) and Hz.
struct Units {
  double d_m = 500e-6;       // mean grain diameter
  double g_mps2 = 9.81;      // gravity
  double length_unit_m = 1;  // one input length unit in metres
  double time_unit_s = 1;    // one input time unit in seconds
  // How the input's units were given: SI, reduced (--units reduced) or by --length-unit and
  // --time-unit (custom); said by input_units_text.
  enum class Input { si, reduced, custom } input = Input::si;
  double velocity_unit_mps() const { return length_unit_m / time_unit_s; }
  double reduced_velocity_mps() const;  // sqrt(g d)
  double reduced_time_s() const;        // sqrt(d / g)
  double reduced_rate_hz() const;       // sqrt(g / d)
  // Input in reduced units: lengths in d, times in sqrt(d/g).
  void use_reduced_input();
};

// "input in SI units (m, s)", "input in reduced units (lengths in d, times in sqrt(d/g))" or
// "input length unit X m, time unit Y s".
std::string input_units_text(const Units& units);

// The files a run directory holds (names relative to it) and their column names.
struct RunColumns {
  std::string time_file = "flow.time";  // fix ave/time, sampled finely (>= 400 Hz)
  std::string timestep = "TimeStep";
  std::string time = "v_time";                 // optional: elapsed time (else TimeStep * dt)
  std::string u_all = "v_u_all";               // optional: mean x-velocity of all grains
  std::string u_flow = "v_u_flow";             // mean x-velocity of the grains with z > 0
  std::string v_flow = "v_v_flow";             // mean z-velocity of the grains with z > 0
  std::string phi = "v_phi_flow";              // optional: area fraction of the flowing layer
  std::string h = "v_h";                       // optional: flowing-layer thickness (else from the profile)
  std::string profile_file = "profile.chunk";  // fix ave/chunk over bin/1d y
  std::string profile_coord = "Coord1";
  std::string profile_vx = "vx";
  std::string profile_count = "Ncount";
  std::string packing_file = "packing.chunk";  // fix ave/chunk over the profile's bins, norm none
  std::string packing_coord = "Coord1";
  std::string packing_phi = "v_phi_of_grain";  // area fraction of the bin
  std::string layers_file = "layers.chunk";    // fix ave/chunk of vy per layer, sampled finely
  std::string layers_coord = "Coord1";
  std::string layers_vz = "vy";
  std::string layers_count = "Ncount";  // optional
  // fix ave/chunk of vy of the flowing layer per x-column, every sample; Coord1 = x / lx
  std::string columns_file = "columns.chunk";
  std::string columns_coord = "Coord1";
  std::string columns_v = "vy";
  std::string columns_count = "Ncount";
};

struct RunSettings {
  std::string directory;
  Units units;
  RunColumns columns;
  std::optional<double> timestep_size;   // input time units per step (--dt)
  std::optional<double> t_start, t_end;  // override of the stationary window, input time units
  // Rate (Hz) of the uniform samples the spectra use (--sample-rate); else the time file's
  // longest sampling interval.
  std::optional<double> sample_rate_hz;
  StationaryCriterion criterion;
  SpectrumOptions spectrum;
  double peak_fmin_hz = 5;
  double peak_fmax_hz = std::numeric_limits<double>::infinity();
  double high_frequency_hz = 100;  // A_mean is the mean amplitude at and above this
  double z0 = 0;                   // wall-top height in input length units (z = y - z0)
  std::string parameters;          // which d, g, z0 and sample rate are used, and where from (one line)
  CreepSettings creep;             // the bins read and the floor of the creep measure
  int averaging_blocks = 10;
  bool progress = false;
  // The cell length L in d (--cell-length): the columns of columns.chunk tile it.
  std::optional<double> cell_length_d;
};

// The samples of the time file on the grid of its sample rate. A run whose step follows the flow
// (fix contact/dynamics dt_max) samples every N steps, so a stretch at a smaller step wrote
// extra samples in between; the step changes only at samples of the grid, so keeping those
// rows is an exact decimation, and time is linear in TimeStep between two of them. A file
// refined from end to end (a short continuation of a fast flow) shows no interval of the grid:
// its rate must be given (RunSettings::sample_rate_hz), or its spectra would reach higher
// frequencies than those of the same run sampled on the grid.
struct TimeSeries {
  std::vector<double> time_s;
  std::vector<double> timestep;  // TimeStep of each kept sample
  size_t rows_read = 0;          // before the decimation
  std::vector<double> u_flow_mps, v_flow_mps;
  std::optional<std::vector<double>> u_all_mps, phi, h_m;
  double sample_interval_s = 0;
};

struct VelocityProfile {
  std::vector<double> z_d, u_reduced, count;  // per bin, averaged over the stationary window
  std::vector<double> phi;                    // area fraction per bin, from packing.chunk (empty without it)
  double bin_width_d = 0;
};

struct LayerSpectrum {
  double z_d = 0;
  Spectrum spectrum;
  SpectralPeak peak;
  double amplitude_at_f = 0;  // at the flowing layer's peak frequency, sqrt(g d)
};

struct RunAnalysis {
  RunSettings settings;
  TimeSeries series;
  Window window;
  bool window_detected = true;
  bool window_stationary = true;  // U drifts across the window within criterion.max_relative_drift
  std::string window_drift;       // that drift against the limit, in words
  Spectrum spectrum;              // of v(t), amplitude in sqrt(g d)
  SpectralPeak peak;
  std::optional<VelocityProfile> profile;
  std::optional<BagnoldFit> bagnold;
  std::optional<CreepMeasure> creep;
  std::optional<PackingProfile> packing;  // phi(z) over the window, every bin (packing.chunk)
  std::vector<LayerSpectrum> layers;
  std::optional<AlongCell> along_cell;  // from columns.chunk
  SolverRecord solver;                  // solver.time and the log's solver lines
  ResultTable results;
  std::vector<std::string> warnings;
  double h_d = 0;  // the layer thickness used for I, U/h and Bagnold (0 if unknown)
};

RunAnalysis analyse_run(const RunSettings& settings);

// How results, report and figures name the analysed window: "stationary window", or
// "window (not stationary)" when it fails the stationarity test.
std::string window_name(const RunAnalysis& run);

// Spectrum, peak and A_mean of one column of a fix ave/time file, over the whole file or
// the window settings.t_start/t_end; amplitudes in the column's own units.
struct ColumnSpectrum {
  Spectrum spectrum;
  SpectralPeak peak;
  ResultTable results;
};
ColumnSpectrum analyse_column_spectrum(const std::string& path, const std::string& column, const RunSettings& settings);

}  // namespace cdpost
