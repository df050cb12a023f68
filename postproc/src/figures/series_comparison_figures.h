// The outputs of two series side by side (analysis/series_comparison.h).
#pragma once

#include <string>

#include "analysis/series_comparison.h"

namespace cdpost {

// OUT/compared_fits.csv (name,unit,A,A_error,B,B_error,difference_sigma with A and B the
// labels), OUT/figures, OUT/report.md.
void write_comparison_outputs(SeriesComparison& comparison, const std::string& out_dir);

}  // namespace cdpost
