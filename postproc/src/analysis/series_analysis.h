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
#include "source/source_numbers.h"

namespace cdpost {

struct SeriesSettings {
  std::string manifest;
  RunSettings run;  // shared by every run; directory set per run
  // Completes the settings of a run read from its raw outputs from what its folder records
  // (the command line's run parameters); none: `run` as it is.
  std::function<void(RunSettings&)> complete_run;
  double beta = 0.136;
  // The values at which the mu(I) rule is refitted with I0 held, and Pouliquen's rule with l
  // held (at beta): the rms residual against the held value shows what the runs determine.
  std::vector<double> held_i0{0.1, 0.15, 0.2, 0.3, 0.4, 0.5};
  std::vector<double> held_ell{0.5, 0.75, 1, 1.25, 1.5, 1.75, 2, 2.5, 3};
  // The numbers of the source study to compare with (source/source_numbers.h); empty: none.
  std::string source_file;
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
  // The deck set the grain count for the source's layer thickness (its `reading layer`,
  // doc/chute.md), so the run's h is not a measurement to compare.
  bool thickness_set_by_deck = false;
};

// One residual of one flow-rule fit.
struct SeriesResidual {
  std::string run;  // the run's directory, as in runs.csv
  double mu = 0, theta_deg = 0;
  std::string fit;       // pouliquen, pouliquen_betafree, muI, phi_U or phi_I, packing_ before the packing definition's
  std::string quantity;  // tan_theta or phi
  double value = 0;      // observed − fitted
};

// A definition of the layer's thickness and packing (doc/scene.md): each run's I and phi under it.
struct LayerDefinition {
  std::string name;         // "surface definition", "packing definition"
  std::string prefix;       // of its fits' names: "" (surface), "packing_"
  std::string inertial;     // the runs' result holding I under it
  std::string phi;          // phi
  std::string thickness;    // and h
  std::string description;  // the definitions, for reports
};
const LayerDefinition kSurfaceDefinition{
    "surface definition", "", "I", "phi", "h", "h = 2 <z>, phi = grain area/(L h)"};
const LayerDefinition kPackingDefinition{
    "packing definition", "packing_",  "I_packing",
    "phi_bulk",           "h_packing", "h = h_packing (phi(z) at half phi_bulk), phi = phi_bulk (0.2 h-0.8 h)"};

// The flow rules and phi laws fitted under one definition.
struct DefinitionFits {
  LayerDefinition definition;
  std::vector<PouliquenFit> pouliquen;  // at the fixed beta
  std::optional<MuIFit> mu_of_i;
  std::optional<PhiFit> phi_of_u, phi_of_i;  // phi = phi_c(mu) - k U/sqrt(g d), - k_I I
};

// A rule refitted with one parameter held: one row per friction.
struct HeldFit {
  std::string definition;  // its prefix: "" or "packing_"
  std::string rule;        // muI (I0 held) or pouliquen (l held)
  double held = 0;
  AngleBounds angles;       // of one friction
  double rms_residual = 0;  // in tan theta, over the fit's runs (every friction for muI)
  int dof = 0;
};

struct SeriesAnalysis {
  SeriesSettings settings;
  std::vector<SeriesRun> runs;                   // the flowing runs, analysed
  std::vector<ManifestEntry> stopped;            // the runs that stopped
  std::vector<DefinitionFits> definitions;       // surface, then packing (when the runs have it)
  std::vector<PouliquenFreeFit> pouliquen_free;  // surface definition
  std::vector<HeldFit> held_fits;
  std::optional<PowerLaw> f_vs_scale, f_vs_shear_rate;
  std::vector<SeriesResidual> residuals;
  ResultTable fits;
  std::vector<std::string> warnings;
  std::optional<SourceNumbers> source;  // read from settings.source_file
};

SeriesAnalysis analyse_series(const SeriesSettings& settings);

}  // namespace cdpost
