// Two series side by side (`cdpost series MANIFEST --compare OTHER`), e.g. the two readings of
// the 45 d cell (doc/scene.md): each series analysed exactly as `cdpost series` analyses it
// alone, every fit of both in one table with their difference in units of the combined error,
// and the series figures with both series on the same axes.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "analysis/series_analysis.h"

namespace cdpost {

struct SeriesComparison {
  std::array<SeriesAnalysis, 2> series;  // the manifest's, then the compared manifest's
  std::array<std::string, 2> labels;     // their names in tables and figures
};

// Names for two manifests: their folders' names (the campaign's series/<analysis>/manifest.csv),
// or their file names without extension when the folders are the same.
std::array<std::string, 2> default_labels(const std::string& manifest, const std::string& other);

// Both series with the same settings, settings.manifest first; the other manifest is read before
// any run is analysed, so that a missing or empty one fails at once.
SeriesComparison compare_series(const SeriesSettings& settings, const std::string& other,
                                const std::array<std::string, 2>& labels);

// One fit name and each series' estimate of it (none where that series has no such fit).
struct ComparedFit {
  std::string name, unit;
  std::array<std::optional<Estimate>, 2> estimates;
  // (second - first) / sqrt(error_first^2 + error_second^2), where both have an error and their
  // combined error is positive.
  std::optional<double> difference_sigma;
};

// The fits of the first series in its order, then those only the second has.
std::vector<ComparedFit> compared_fits(const SeriesComparison& comparison);

// The warnings of both series, each led by its series' label.
std::vector<std::string> comparison_warnings(const SeriesComparison& comparison);

}  // namespace cdpost
