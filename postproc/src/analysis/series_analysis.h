// The analysis of a series of runs: each run analysed as by `cdpost run`, then the flow
// rules, the phi(U) law, the scaling of f and A, and the L dependence.
//
// The manifest is a CSV with a header naming at least run, mu and theta (degrees) and
// optionally L (cell length in d), stopped (0 or 1) and h_stop (deposit thickness in d, given
// exactly for the runs with stopped = 1); run is a directory, relative to the manifest: a run's
// raw outputs, analysed again, or a run published by `cdpost run` (results.csv and layers.csv
// at its top, analysis/published_run.h), read as it is. A stopped run is not read: its row is
// the measurement h_stop(theta) for Pouliquen's rule.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/run_analysis.h"
#include "fit/flow_rules.h"
#include "fit/profile_fits.h"

namespace cdpost {

struct SeriesSettings {
  std::string manifest;
  RunSettings run;  // shared by every run; directory set per run
  // Completes the settings of a run read from its raw outputs from what its folder records
  // (the command line's run parameters); none: `run` as it is.
  std::function<void(RunSettings&)> complete_run;
  double beta = 0.136;
};

struct ManifestEntry {
  std::string name;       // as written in the manifest
  std::string directory;  // relative to the working directory
  double mu = 0;
  double theta_deg = 0;
  std::optional<double> length_d;
  bool stopped = false;
  std::optional<double> h_stop_d;  // exactly when stopped
  long line = 0;
};

std::vector<ManifestEntry> read_manifest(const std::string& path);

struct SeriesRun {
  ManifestEntry entry;
  RunAnalysis analysis;
  double value(const std::string& name) const;  // a result every run has (U, f, A, ...)
  std::optional<Estimate> estimate(const std::string& name) const;
  std::optional<DepthDecay> depth_decay;  // of the amplitude at f over the layers
};

// One residual of one flow-rule fit.
struct SeriesResidual {
  std::string run;  // the run's directory, as in runs.csv
  double mu = 0, theta_deg = 0;
  std::string fit;       // pouliquen, pouliquen_betafree, muI or phi_U
  std::string quantity;  // tan_theta or phi
  double value = 0;      // observed − fitted
};

struct SeriesAnalysis {
  SeriesSettings settings;
  std::vector<SeriesRun> runs;          // the flowing runs, analysed
  std::vector<ManifestEntry> stopped;   // the runs that stopped
  std::vector<PouliquenFit> pouliquen;  // at the fixed beta
  std::vector<PouliquenFreeFit> pouliquen_free;
  std::optional<MuIFit> mu_of_i;
  std::optional<PhiFit> phi_of_u;
  std::optional<PowerLaw> f_vs_scale, f_vs_shear_rate;
  std::vector<SeriesResidual> residuals;
  ResultTable fits;
  std::vector<std::string> warnings;
};

SeriesAnalysis analyse_series(const SeriesSettings& settings);

// OUT/runs.csv (one row per flowing run), OUT/fits.{csv,json}, OUT/residuals.csv,
// OUT/layer_amplitudes.csv, OUT/depth_decay.csv, OUT/figures, OUT/report.md.
void write_series_outputs(SeriesAnalysis& series, const std::string& out_dir);

}  // namespace cdpost
