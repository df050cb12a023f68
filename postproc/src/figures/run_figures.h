// The outputs of one run (analysis/run_analysis.h): tables, figures and the Markdown report.
#pragma once

#include <string>
#include <vector>

#include "analysis/run_analysis.h"

namespace cdpost {

// Writes OUT/results.{csv,json}, OUT/spectrum.csv, OUT/profile.csv, OUT/layers.csv,
// OUT/space_time.csv and OUT/coherence.csv (with columns.chunk), the figures in OUT/figures
// and OUT/report.md. `dump` (optional) adds a snapshot, the atoms of `obstacle_types` drawn as obstacles.
void write_run_outputs(RunAnalysis& run, const std::string& out_dir, const std::string& dump_path,
                       const std::vector<long>& obstacle_types = {});

}  // namespace cdpost
