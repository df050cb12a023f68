// Figures, data tables and the Markdown report of one run.
#include "figures/run_figures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "figures/along_cell_figures.h"
#include "figures/snapshot.h"
#include "output/gnuplot.h"
#include "output/report.h"

namespace cdpost {

namespace {

std::vector<double> reduced(const std::vector<double>& values, double scale)
{
  std::vector<double> out;
  for (double v : values) out.push_back(v / scale);
  return out;
}

Figure time_series_figure(const RunAnalysis& run)
{
  const auto& s = run.series;
  const auto& units = run.settings.units;
  const auto t = reduced(s.time_s, units.reduced_time_s());
  const std::pair<double, double> band{t[run.window.begin], t[run.window.end - 1]};
  Panel u;
  u.title = "Mean x-velocity; shaded: " + window_name(run);
  u.x_label = "t / sqrt(d/g)";
  u.y_label = "velocity / sqrt(g d)";
  u.x_band = band;
  u.curves.push_back(
      make_curve("U(t), grains with z > 0", CurveStyle::Lines, t, reduced(s.u_flow_mps, units.reduced_velocity_mps())));
  if (s.u_all_mps)
    u.curves.push_back(
        make_curve("u(t), all grains", CurveStyle::Lines, t, reduced(*s.u_all_mps, units.reduced_velocity_mps())));
  u.origin_y = 0.5;
  u.height = 0.5;
  Panel v;
  v.title = "Mean normal velocity v(t) of the flowing layer";
  v.x_label = u.x_label;
  v.y_label = "v / sqrt(g d)";
  v.x_band = band;
  v.key = "off";
  v.curves.push_back(make_curve("v(t)", CurveStyle::Lines, t, reduced(s.v_flow_mps, units.reduced_velocity_mps())));
  v.height = 0.5;
  return {"u_t", "u(t), U(t) and v(t) of the run", {u, v}, 900, 800};
}

Figure spectrum_figure(const RunAnalysis& run)
{
  Panel panel;
  panel.title = "Amplitude spectrum of v(t) (Hann, " + std::to_string(run.spectrum.segments) + " segments of " +
                format_estimate(run.spectrum.segment_duration_s, std::nullopt) + " s)";
  panel.x_label = "f (Hz)";
  panel.y_label = "A / sqrt(g d)";
  panel.key = "top right";
  // A spectrum of a changing flow reads like any other: the panel says so where it is seen.
  if (!run.window_stationary)
    panel.title = "NOT STATIONARY (" + run.window_drift.substr(0, run.window_drift.find(',')) + "): " + panel.title;
  panel.curves.push_back(make_curve("A(f)", CurveStyle::Lines, run.spectrum.frequency_hz, run.spectrum.amplitude));
  Curve peak = make_curve("peak f = " + format_estimate(run.peak.frequency_hz, run.peak.frequency_error_hz) + " Hz",
                          CurveStyle::Points, {run.peak.frequency_hz}, {run.peak.amplitude});
  panel.curves.push_back(peak);
  if (const auto* a_mean = run.results.find("A_mean"))
    panel.curves.push_back(make_curve(
        "A_mean (f >= " + format_estimate(run.settings.high_frequency_hz, std::nullopt) + " Hz)", CurveStyle::Lines,
        {run.settings.high_frequency_hz, run.spectrum.frequency_hz.back()}, {a_mean->value, a_mean->value}));
  return {"spectrum", "Spectrum of v(t) over the " + window_name(run), {panel}};
}

// u(z) > 0 below the wall tops in semi-log: the fit range's bins filled, the others open, the
// fit over its range and the floor and kFloorMultiple x the floor as dashed lines.
std::optional<Panel> creep_inset(const VelocityProfile& p, const std::optional<CreepMeasure>& creep)
{
  std::vector<double> fitted_u, fitted_z, other_u, other_z;
  const bool resolved = creep && creep->lambda;
  for (size_t i = 0; i < p.z_d.size(); ++i) {
    if (!(p.z_d[i] < 0 && p.u_reduced[i] > 0)) continue;
    const bool in_range = resolved && p.z_d[i] >= creep->z_low && p.z_d[i] <= creep->z_high;
    (in_range ? fitted_u : other_u).push_back(p.u_reduced[i]);
    (in_range ? fitted_z : other_z).push_back(p.z_d[i]);
  }
  if (fitted_u.size() + other_u.size() < 2) return std::nullopt;
  Panel inset;
  inset.title = "creep (z < 0)";
  inset.x_label = "u / sqrt(g d)";
  inset.y_label = "z / d";
  inset.log_x = true;
  inset.key = "off";
  inset.origin_x = 0.52;
  inset.origin_y = 0.1;
  inset.width = 0.45;
  inset.height = 0.45;
  Curve outside = make_curve("u(z)", CurveStyle::Points, other_u, other_z);
  outside.line_type = 1;
  outside.point_type = 6;  // open circles
  if (!other_u.empty()) inset.curves.push_back(outside);
  if (resolved) {
    Curve inside = make_curve("u(z), fit range", CurveStyle::Points, fitted_u, fitted_z);
    inside.line_type = 1;
    inset.curves.push_back(inside);
    std::vector<double> z{creep->z_low, creep->z_high}, u;
    for (double zi : z) u.push_back(creep->u0->value * std::exp(zi / creep->lambda->value));
    inset.curves.push_back(make_curve("lambda fit", CurveStyle::Lines, u, z));
  }
  if (creep && creep->floor) {
    const double bottom = std::min(p.z_d.front(), p.z_d.back());
    for (double multiple : {1.0, kFloorMultiple}) {
      Curve floor = make_curve(multiple == 1 ? "floor" : "10 x floor", CurveStyle::Lines,
                               std::vector<double>(2, multiple * creep->floor->value), {bottom, 0.0});
      floor.dashed = true;
      floor.line_type = 3;
      inset.curves.push_back(floor);
    }
  }
  return inset;
}

Figure profile_figure(const RunAnalysis& run)
{
  const auto& p = *run.profile;
  Panel main;
  main.title = "Velocity profile u(z)";
  main.x_label = "u / sqrt(g d)";
  main.y_label = "z / d";
  // Bins above the measured h hold the few grains of the dilute surface, outside the fit: drawn
  // open and named, so that they do not read as a failure of the Bagnold shape.
  std::vector<double> u_layer, z_layer, u_above, z_above;
  for (size_t i = 0; i < p.z_d.size(); ++i) {
    const bool above = run.bagnold && p.z_d[i] > run.bagnold->h;
    (above ? u_above : u_layer).push_back(p.u_reduced[i]);
    (above ? z_above : z_layer).push_back(p.z_d[i]);
  }
  Curve layer = make_curve("u(z)", CurveStyle::Points, u_layer, z_layer);
  layer.line_type = 1;
  main.curves.push_back(layer);
  if (!u_above.empty()) {
    Curve surface =
        make_curve("u(z) above h: dilute surface, few grains, not fitted", CurveStyle::Points, u_above, z_above);
    surface.line_type = 1;
    surface.point_type = 6;  // open circles
    main.curves.push_back(surface);
  }
  if (run.bagnold) {
    std::vector<double> z, u;
    for (double zi = 0; zi <= run.bagnold->h; zi += run.bagnold->h / 100) {
      z.push_back(zi);
      u.push_back(bagnold_velocity(*run.bagnold, zi));
    }
    Curve fit =
        make_curve("Bagnold fit, h = " + format_estimate(run.bagnold->h, std::nullopt) + " d", CurveStyle::Lines, u, z);
    fit.line_type = 2;
    main.curves.push_back(fit);
  }
  Figure figure{"profile",
                "u(z) with the Bagnold fit over 0 <= z <= h (open: the bins above h, the dilute surface); inset: creep "
                "below z = 0 (semi-log): filled, the bins of the creep fit range with its fit; dashed, the floor and "
                "10 x the floor",
                {main}};
  if (auto inset = creep_inset(p, run.creep)) figure.panels.push_back(*inset);
  return figure;
}

Figure depth_figure(const RunAnalysis& run)
{
  Panel spectra;
  spectra.title = "Spectra of v(t) by layer";
  spectra.x_label = "f (Hz)";
  spectra.y_label = "A / sqrt(g d)";
  spectra.key = "top right";
  spectra.height = 0.6;
  spectra.origin_y = 0.4;
  const size_t shown = std::min<size_t>(6, run.layers.size());
  for (size_t i = 0; i < shown; ++i) {
    const auto& layer =
        run.layers[run.layers.size() - 1 - i * (run.layers.size() - 1) / std::max<size_t>(1, shown - 1)];
    spectra.curves.push_back(make_curve("z = " + format_estimate(layer.z_d, std::nullopt) + " d", CurveStyle::Lines,
                                        layer.spectrum.frequency_hz, layer.spectrum.amplitude));
  }
  Panel decay;
  decay.title = "Amplitude at f = " + format_estimate(run.peak.frequency_hz, std::nullopt) + " Hz against depth";
  decay.x_label = "z / d";
  decay.y_label = "A(f) / sqrt(g d)";
  decay.key = "off";
  decay.height = 0.4;
  std::vector<double> z, a;
  for (const auto& layer : run.layers) {
    z.push_back(layer.z_d);
    a.push_back(layer.amplitude_at_f);
  }
  decay.curves.push_back(make_curve("A(f, z)", CurveStyle::LinesPoints, z, a));
  return {"spectra_depth", "Depth-resolved spectra of v(t)", {spectra, decay}, 900, 900};
}

void write_tables(const RunAnalysis& run, const std::string& out)
{
  write_columns_csv(out + "/spectrum.csv", {"f_Hz", "A_sqrt_gd"}, {run.spectrum.frequency_hz, run.spectrum.amplitude});
  if (run.profile) {
    std::vector<std::string> names{"z_d", "u_sqrt_gd", "count"};
    std::vector<std::vector<double>> columns{run.profile->z_d, run.profile->u_reduced, run.profile->count};
    if (!run.profile->phi.empty()) names.push_back("phi"), columns.push_back(run.profile->phi);
    write_columns_csv(out + "/profile.csv", names, columns);
  }
  if (!run.layers.empty()) {
    std::vector<std::vector<double>> columns(5);
    for (const auto& layer : run.layers) {
      columns[0].push_back(layer.z_d);
      columns[1].push_back(layer.peak.frequency_hz);
      columns[2].push_back(layer.peak.frequency_error_hz);
      columns[3].push_back(layer.peak.amplitude);
      columns[4].push_back(layer.amplitude_at_f);
    }
    write_columns_csv(out + "/layers.csv", {"z_d", "f_peak_Hz", "f_error_Hz", "A_peak_sqrt_gd", "A_at_f_sqrt_gd"},
                      columns);
  }
}

std::string method_text(const RunAnalysis& run)
{
  const auto& s = run.settings;
  std::string window =
      run.window_detected
          ? "Stationary window detected: earliest start at which the line fitted to U(t) drifts by at most " +
                format_estimate(s.criterion.max_relative_drift * 100, std::nullopt) +
                "% of the mean across a window of at least " +
                format_estimate(s.criterion.min_window_fraction * 100, std::nullopt) + "% of the run"
          : (run.window_stationary ? "Stationary window" : "Window") + std::string(" given on the command line, ") +
                (run.window_stationary ? "" : "not stationary: ") + run.window_drift;
  return "Units: " + input_units_text(s.units) + "; d = " + format_estimate(s.units.d_m, std::nullopt) +
         " m, g = " + format_estimate(s.units.g_mps2, std::nullopt) +
         " m/s^2 (sqrt(g/d) = " + format_estimate(s.units.reduced_rate_hz(), std::nullopt) + " Hz)" +
         (s.units.input == Units::Input::reduced ? ", which turn the reduced input's times into s and Hz" : "") + ". " +
         window + ". Means carry the standard error of " + std::to_string(s.averaging_blocks) +
         " block means. Spectrum: Welch average of Hann-windowed, detrended segments of " +
         format_estimate(run.spectrum.segment_duration_s, std::nullopt) +
         " s, amplitude normalised so that a sinusoid of amplitude a reads a; "
         "f is the maximum in [" +
         format_estimate(s.peak_fmin_hz, std::nullopt) + " Hz, " +
         format_estimate(std::min(s.peak_fmax_hz, run.spectrum.frequency_hz.back()), std::nullopt) +
         " Hz], its error the half width at half power.";
}

}  // namespace

void write_run_outputs(RunAnalysis& run, const std::string& out_dir, const std::string& dump_path,
                       const std::vector<long>& obstacle_types)
{
  const std::string figures_dir = out_dir + "/figures";
  std::filesystem::create_directories(figures_dir);
  std::vector<Figure> figures{time_series_figure(run), spectrum_figure(run)};
  if (run.profile) figures.push_back(profile_figure(run));
  if (!run.layers.empty()) figures.push_back(depth_figure(run));
  if (run.along_cell) figures.push_back(along_cell_figure(*run.along_cell));
  if (!dump_path.empty()) {
    SnapshotRequest request;
    request.dump_path = dump_path;
    request.progress = run.settings.progress;
    request.wall_tops = run.settings.z0;
    request.obstacle_types = obstacle_types;
    figures.push_back(snapshot_figure(request, run.settings.units).figure);
  }
  MarkdownReport report("Run " + run.settings.directory);
  report.paragraph(method_text(run));
  if (!run.settings.parameters.empty()) report.paragraph("Parameters: " + run.settings.parameters + ".");
  report.heading("Solver health");
  report.paragraph(solver_health_text(run.solver));
  report.heading("Results");
  report.table(run.results);
  if (run.creep) {
    report.heading("Creep below the wall tops");
    report.paragraph(creep_summary(*run.creep) + " (doc/postproc.md, The creep measure.)");
  }
  if (run.along_cell) {
    report.heading("Along the cell");
    report.paragraph(along_cell_text(*run.along_cell, window_name(run)));
  }
  report.heading("Figures");
  for (const auto& figure : figures) {
    if (auto problem = render_figure(figure, figures_dir)) run.warnings.push_back(*problem);
    else report.figure("figures", figure.name, figure.caption);
  }
  report.warnings(run.warnings);
  write_tables(run, out_dir);
  if (run.along_cell) write_along_cell_tables(*run.along_cell, out_dir);
  run.results.write_csv(out_dir + "/results.csv");
  run.results.write_json(out_dir + "/results.json", run.warnings);
  report.write(out_dir + "/report.md");
}

}  // namespace cdpost
