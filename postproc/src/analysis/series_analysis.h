// The analysis of a series of runs: each run analysed as by `cdpost run`, then the flow
// rules, the phi(U) law, the scaling of f and A, and the L dependence.
//
// The manifest is a CSV with a header naming at least run, mu and theta (degrees) and
// optionally L (cell length in d); run is a directory, relative to the manifest.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/run_analysis.h"
#include "fit/flow_rules.h"

namespace cdpost {

struct SeriesSettings {
  std::string manifest;
  RunSettings run;  // shared by every run; directory set per run
  double beta = 0.136;
};

struct ManifestEntry {
  std::string directory;
  double mu = 0;
  double theta_deg = 0;
  std::optional<double> length_d;
  long line = 0;
};

std::vector<ManifestEntry> read_manifest(const std::string& path);

struct SeriesRun {
  ManifestEntry entry;
  RunAnalysis analysis;
  double value(const std::string& name) const;  // a result every run has (U, f, A, ...)
  std::optional<Estimate> estimate(const std::string& name) const;
};

struct SeriesAnalysis {
  SeriesSettings settings;
  std::vector<SeriesRun> runs;
  std::vector<PouliquenFit> pouliquen;
  std::optional<MuIFit> mu_of_i;
  std::optional<PhiFit> phi_of_u;
  std::optional<PowerLaw> f_vs_scale, f_vs_shear_rate;
  ResultTable fits;
  std::vector<std::string> warnings;
};

SeriesAnalysis analyse_series(const SeriesSettings& settings);

// OUT/runs.csv (one row per run), OUT/fits.{csv,json}, OUT/figures, OUT/report.md.
void write_series_outputs(SeriesAnalysis& series, const std::string& out_dir);

}  // namespace cdpost
