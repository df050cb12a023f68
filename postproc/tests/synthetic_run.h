// A synthetic run directory in the layout the chute decks write (SI units), with known
// U, phi, h, oscillation frequency and amplitude, Bagnold profile and creep length, and a packing
// profile of known bulk phi and half-height.
#pragma once

#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "lammps_text.h"
#include "temp_files.h"

namespace cdpost::testing {

struct SyntheticRun {
  double d = 5e-4, g = 9.81;
  double dt = 1e-5;         // s per step
  long output_every = 100;  // steps: 1 kHz sampling
  double duration = 6.0;    // s
  double relaxation = 0.4;  // s, transient of U
  double u_final = 10.0;    // sqrt(g d)
  double h = 40.0;          // d
  double phi = 0.78;
  double frequency = 37.0;    // Hz
  double amplitude = 0.2;     // sqrt(g d)
  double noise = 0.3;         // sqrt(g d), white noise on v(t)
  double creep_lambda = 3.0;  // d
  // sqrt(g d): sign-changing noise on u below the wall tops in each profile block, the solver's
  // floor (the creep measure estimates it from the deep bed)
  double bed_noise = 1e-3;
  double phi_bed = 0.82;    // packing below the wall tops
  double phi_bulk = 0.80;   // packing of the layer's bulk, falling to half of it at z = h
  double tail_width = 2.0;  // d, width of the dilute surface: phi = phi_bulk erfc((z - h)/w)/2
  unsigned seed = 1;
  double y_top = 0;  // m: height of the wall tops, z = y - y_top
  bool with_chunks_and_dump = true;
  double occupied_above_h = 0;  // d: profile bins above h holding grains (a dilute surface), u as at h
  bool with_record = true;      // chute.params, as inputs/in.chute writes it
  // solver.time, as inputs/in.chute writes it (every 10000 steps, every step converged but these)
  bool with_solver = true;
  long unconverged_steps = 0;               // all in the first interval
  std::optional<double> recorded_length_d;  // L_d of chute.params (none: not recorded)
  // columns.chunk: v of `columns` x-columns tiling the cell, each the layer's oscillation plus
  // noise of its own (column_noise); one column empty every `empty_every` samples (0: never).
  bool with_columns = false;
  size_t columns = 30;
  double column_noise = 0.1;  // sqrt(g d)
  long empty_every = 40;

  double v0() const { return std::sqrt(g * d); }
  double u_of_t(double t) const { return u_final * (1 - std::exp(-t / relaxation)); }
  // Bagnold above the bed with u(h) = u_surface, exponential creep below.
  double u_of_z(double z) const
  {
    const double slip = 0.3, surface = 2 * u_final;
    if (z < 0) return slip * std::exp(z / creep_lambda);
    return slip + (surface - slip) * (std::pow(h, 1.5) - std::pow(h - std::min(z, h), 1.5)) / std::pow(h, 1.5);
  }
  // Antisymmetric about z = h: on bins centred h ± 0.5 d, linear interpolation finds h exactly.
  double phi_of_z(double z) const { return z < 0 ? phi_bed : 0.5 * phi_bulk * std::erfc((z - h) / tail_width); }
};

inline void write_synthetic_run(const std::filesystem::path& dir, const SyntheticRun& run)
{
  std::filesystem::create_directories(dir);
  std::mt19937 rng(run.seed);
  std::normal_distribution<double> gauss(0, 1);
  const double v0 = run.v0();
  const long steps = static_cast<long>(run.duration / run.dt);

  std::vector<std::vector<double>> rows;
  for (long step = run.output_every; step <= steps; step += run.output_every) {
    const double t = step * run.dt;
    const double v = run.amplitude * std::sin(2 * M_PI * run.frequency * t) + run.noise * gauss(rng);
    rows.push_back({double(step), t, 0.5 * run.u_of_t(t) * v0, (run.u_of_t(t) + 0.05 * gauss(rng)) * v0, v * v0,
                    run.phi + 0.005 * gauss(rng), (run.h + 0.3 * gauss(rng)) * run.d});
  }
  write_file(dir / "flow.time",
             ave_time_text({"TimeStep", "v_time", "v_u_all", "v_u_flow", "v_v_flow", "v_phi_flow", "v_h"}, rows));
  if (run.with_solver) {
    std::vector<std::vector<double>> solver;
    for (long step = 10000; step <= steps; step += 10000)
      solver.push_back({double(step), 40, 1e-4, 100, 80, 1e-3, 1e-4,
                        step == 10000 ? 1 - double(run.unconverged_steps) / 10000 : 1.0, 2, 1});
    write_file(dir / "solver.time", ave_time_text({"TimeStep", "f_cd[1]", "f_cd[2]", "f_cd[3]", "f_cd[4]", "f_cd[5]",
                                                   "f_cd[6]", "f_cd[7]", "f_cd[11]", "f_cd[12]"},
                                                  solver));
  }
  if (run.with_record) {
    std::ostringstream record;
    record << "# inputs/in.chute: chute parameters, one name and value a line (SI)\ny_top_m " << run.y_top
           << "\nsample_rate_hz " << 1 / (run.dt * run.output_every) << "\nd_m " << run.d << "\ng_mps2 " << run.g
           << "\ntheta_deg 24\n";
    if (run.recorded_length_d) record << "L_d " << *run.recorded_length_d << "\n";
    write_file(dir / "chute.params", record.str());
  }
  if (!run.with_chunks_and_dump) return;

  std::vector<long> profile_steps;
  for (long step = 10000; step <= steps; step += 10000) profile_steps.push_back(step);
  const size_t bins = 80;              // z from -30 d to 50 d
  std::mt19937 bed_rng(run.seed + 1);  // its own stream: the other files' noise as without it
  std::normal_distribution<double> bed_gauss(0, 1);
  auto z_of = [&](size_t bin) { return -30.0 + bin + 0.5; };
  write_file(dir / "profile.chunk",
             ave_chunk_text({"Coord1", "Ncount", "vx"}, profile_steps, bins, [&](size_t, size_t bin, size_t column) {
               const double z = z_of(bin);
               const bool occupied = z < run.h + run.occupied_above_h;
               if (column == 0) return z * run.d + run.y_top;
               if (column == 1) return occupied ? 20.0 : 0.0;
               if (!occupied) return 0.0;
               const double floor = z < 0 ? run.bed_noise * bed_gauss(bed_rng) : 0.0;
               return (run.u_of_z(z) * std::exp(0.02 * gauss(rng)) + floor) * v0;
             }));

  write_file(dir / "packing.chunk", ave_chunk_text({"Coord1", "Ncount", "v_phi_of_grain"}, profile_steps, bins,
                                                   [&](size_t, size_t bin, size_t column) {
                                                     const double z = z_of(bin);
                                                     if (column == 0) return z * run.d + run.y_top;
                                                     if (column == 1) return z < run.h ? 20.0 : 0.0;
                                                     return run.phi_of_z(z);
                                                   }));

  std::vector<long> layer_steps;
  for (long step = run.output_every; step <= steps; step += run.output_every) layer_steps.push_back(step);
  write_file(dir / "layers.chunk",
             ave_chunk_text({"Coord1", "Ncount", "vy"}, layer_steps, 6, [&](size_t block, size_t layer, size_t column) {
               const double z = -5.0 + 10.0 * layer;  // -5 ... 45 d; the top layer is empty
               if (column == 0) return z * run.d + run.y_top;
               if (column == 1) return z < run.h ? 30.0 : 0.0;
               if (z >= run.h) return 0.0;
               const double t = layer_steps[block] * run.dt;
               const double depth_factor = std::exp((z - run.h) / 20.0);
               return (run.amplitude * depth_factor * std::sin(2 * M_PI * run.frequency * t) + 0.1 * gauss(rng)) * v0;
             }));

  if (run.with_columns)
    write_file(
        dir / "columns.chunk",
        ave_chunk_text(
            {"Coord1", "Ncount", "vy"}, layer_steps, run.columns, [&](size_t block, size_t column, size_t value) {
              const bool empty = run.empty_every > 0 && column == 2 && static_cast<long>(block) % run.empty_every == 0;
              if (value == 0) return (column + 0.5) / run.columns;
              if (value == 1) return empty ? 0.0 : 40.0;
              if (empty) return 0.0;
              const double t = layer_steps[block] * run.dt;
              return (run.amplitude * std::sin(2 * M_PI * run.frequency * t) + run.column_noise * gauss(rng)) * v0;
            }));

  std::vector<DumpAtom> atoms;
  for (long id = 1; id <= 300; ++id) {
    const double x = (id % 30 + 0.5) * run.d * 1.5, z = ((id / 30) - 3.0) * run.d * 1.5;
    atoms.push_back({id, x, z + run.y_top, run.u_of_z(z / run.d) * v0, 0, 0.5 * run.d});
  }
  write_gzip(dir / "dump.chute.gz", dump_frame_text(0, 45 * run.d, 60 * run.d + run.y_top, atoms) +
                                        dump_frame_text(steps, 45 * run.d, 60 * run.d + run.y_top, atoms));
}

}  // namespace cdpost::testing
