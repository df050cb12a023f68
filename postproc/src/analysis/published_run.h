// A run as `cdpost run` published it: results.csv and layers.csv in a folder (results/runs/<name>
// of the campaign keeps these, without the raw outputs). `cdpost series` reads such a folder as
// it is, so the series fits can be made again from published results alone; its results are
// those of the analysis that wrote it (window, blocks, options), not analysed again; its u(z) and
// phi(z) are read from profile.csv, and phi_bulk, h_packing and I_packing added from them when
// results.csv lacks them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/run_analysis.h"
#include "fit/creep.h"

namespace cdpost {

// A folder holding results.csv directly (a run folder of raw outputs keeps it under post/).
bool is_published_run(const std::string& directory);

// Results and, when layers.csv and profile.csv are present, the layers' z and amplitude at f and
// the profile u(z), phi(z). Malformed files
// fail with one line naming the file, the line and the problem.
RunAnalysis read_published_run(const std::string& directory);

// profile.csv as `cdpost run` writes it: z_d, u_sqrt_gd, count per bin and phi where the run's
// analysis had packing.chunk (else empty).
struct PublishedProfile {
  std::vector<double> z_d, u, count, phi;
};
PublishedProfile read_published_profile(const std::string& path);

// The deck variable `name` as the run folder's params.json records it (the campaign's record);
// none without the file or the variable.
std::optional<std::string> recorded_deck_variable(const std::string& directory, const std::string& name);

// Replaces the creep_* rows of a published run's results.csv and results.json by `creep`'s
// (where the first of them stood, else at the end), keeping every other row and warning but
// the earlier creep warnings; the new creep warnings are added.
void update_published_creep(const std::string& directory, const CreepMeasure& creep);

}  // namespace cdpost
