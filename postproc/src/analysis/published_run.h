// A run as `cdpost run` published it: results.csv and layers.csv in a folder (results/runs/<name>
// of the campaign keeps these, without the raw outputs). `cdpost series` reads such a folder as
// it is, so the series fits can be made again from published results alone; its results are
// those of the analysis that wrote it (window, blocks, options), not analysed again; only
// phi_bulk, h_packing and I_packing are added from profile.csv when results.csv lacks them.
#pragma once

#include <string>

#include "analysis/run_analysis.h"

namespace cdpost {

// A folder holding results.csv directly (a run folder of raw outputs keeps it under post/).
bool is_published_run(const std::string& directory);

// Results and, when layers.csv is present, the layers' z and amplitude at f. Malformed files
// fail with one line naming the file, the line and the problem.
RunAnalysis read_published_run(const std::string& directory);

}  // namespace cdpost
