// Rigid and soft-sphere runs of one chute, side by side: each run directory is analysed as by
// `cdpost run` (same window rule, spectrum and means), then the soft runs' spectra are read
// against their contact frequency sqrt(2k/m)/(2 pi), the overlaps they reached are measured
// from their dumps, and the cost per physical second is taken from their logs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/run_analysis.h"
#include "output/results.h"
#include "overlaps.h"
#include "run_info.h"

namespace cdref {

struct CompareSettings {
  std::vector<std::string> run_dirs;
  cdpost::RunSettings run;         // units, window overrides, spectrum, columns
  double flow_band_max_hz = 500;   // the flow's own oscillation is sought in [fmin, this]
  double contact_band_low = 0.25;  // the contact band is [low, high] x f_contact
  double contact_band_high = 4.0;
  double smoothing = 0.1;                // contact band: relative half-width of the smoothing
  double peak_excess = 1.5;              // a contact-band peak stands this far above the band's power law
  std::string dump_name = "dump.chute";  // in each run directory; overlaps skipped if absent
  std::string commands_file;             // optional: the commands that made the runs, quoted in the report
};

struct ComparedRun {
  std::string directory;
  std::string label;  // unique, e.g. "granular hooke 1e-3"
  std::string code;   // run.info "code" (lmp_cd, lammps-granular, liggghts), or "unknown"
  std::string model;  // rigid, hooke, hertz, or "unknown"
  RunInfo info;
  cdpost::RunAnalysis analysis;
  bool stationary = true;   // false: no stationary regime was detected (second half analysed)
  std::string window_note;  // how the window was chosen
  std::optional<double> k_eff_n_per_m, k_reduced, f_contact_hz, overlap_target;
  std::optional<OverlapStatistics> overlaps;
  std::optional<double> loop_seconds, physical_seconds, cpu_percent;
  std::optional<double> process_cpu_share;           // (user + sys) / wall of the whole process (timing.txt)
  std::optional<cdpost::SpectralPeak> flow_peak;     // in [fmin, flow_band_max]
  std::optional<cdpost::SpectralPeak> contact_peak;  // in the contact band (soft runs), if prominent
  std::optional<double> contact_excess;              // contact band: max of A / fitted power law

  bool soft() const { return f_contact_hz.has_value(); }
  std::optional<double> wall_per_physical_second() const;
  // The flow loop's wall time times the process's CPU share (timing.txt, else LAMMPS's CPU
  // use): the cost on a core of its own, when other jobs shared the machine.
  std::optional<double> cpu_per_physical_second() const;
};

struct Comparison {
  std::vector<ComparedRun> runs;
  cdpost::ResultTable fits;  // how the peaks move with k, per code and model
  std::vector<std::string> warnings;
};

Comparison compare_runs(const CompareSettings& settings);

// OUT/table.csv, OUT/fits.csv, OUT/spectra.csv, OUT/profiles.csv, OUT/figures/*, OUT/report.md.
void write_comparison(Comparison& comparison, const CompareSettings& settings, const std::string& out_dir);

}  // namespace cdref
