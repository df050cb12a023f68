// The outputs of the along-cell analysis of one run (analysis/along_cell.h).
#pragma once

#include <string>

#include "analysis/along_cell.h"
#include "output/gnuplot.h"

namespace cdpost {

// OUT/space_time.csv (m, k, f, power) and OUT/coherence.csv (r, C, pairs, fit).
void write_along_cell_tables(const AlongCell& along, const std::string& out_dir);
// The (k, f) map of log10 power and the coherence against distance with its fit.
Figure along_cell_figure(const AlongCell& along);
// The report's paragraph: method, then the verdict; `window` names the time window analysed
// ("stationary window", or a forced one labelled not stationary: window_name).
std::string along_cell_text(const AlongCell& along, const std::string& window);

}  // namespace cdpost
