// The along-cell results of a series (analysis/along_cell.h): per run the verdict and the
// coherence length, as a CSV, a report section and a figure against U per friction.
#pragma once

#include <string>
#include <vector>

#include "analysis/series_analysis.h"
#include "output/gnuplot.h"
#include "output/report.h"

namespace cdpost {

// One curve per friction coefficient of result y (with its error bars if any) against result x
// ("theta": the tilt); runs without either are left out (series_figures.cpp).
std::vector<Curve> by_friction(const SeriesAnalysis& series, const std::string& x, const std::string& y);

// OUT/along_cell.csv (one row per run with an oscillation_pattern), the report's section and the
// figure OUT/figures/coherence_vs_U; a paragraph saying so when no run has them.
void along_cell_section(SeriesAnalysis& series, MarkdownReport& report, const std::string& out_dir);

}  // namespace cdpost
