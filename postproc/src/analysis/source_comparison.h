// A series against the numbers of its source (analysis/source_numbers.h): curves compared as
// curves (each run against the source's rule at the run's own I, h and U), ranges as ranges,
// signs as signs with their errors; the fit parameters that the runs cannot separate (3
// parameters over a few angles) shown apart as degenerate, with their correlation; and the
// source's own two flow rules checked against each other.
#pragma once

#include <string>
#include <vector>

#include "analysis/series_analysis.h"
#include "analysis/series_figures.h"
#include "output/report.h"

namespace cdpost {

enum class Verdict { Agrees, Outside, NotATarget, Shown };
std::string verdict_text(Verdict verdict);

// One comparison of a series with its source.
struct SourceRow {
  std::string key;        // the source row compared (source.csv's name, with the friction's suffix)
  std::string quantity;   // what is compared
  std::string source;     // the source's number
  std::string tolerance;  // what counts as agreeing
  std::string ours;       // the series' reading
  Verdict verdict = Verdict::Shown;
};

// Every comparison the series has the data for (none without a source).
std::vector<SourceRow> compare_with_source(const SeriesAnalysis& series);

// A fit parameter the runs do not determine apart from another (correlation near +-1).
struct DegenerateRow {
  std::string name, source, ours, correlation;
};
std::vector<DegenerateRow> degenerate_parameters(const SeriesAnalysis& series);

// The comparisons of one or two series (the campaign's two readings), under their labels.
struct LabelledSeries {
  std::string label;
  const SeriesAnalysis* series;
};
// The report's section "Against the source" and OUT/source_comparison.csv
// (key,quantity,source,<label>...,tolerance,verdict_<label>...).
void source_section(MarkdownReport& report, const std::vector<LabelledSeries>& series);
void write_source_comparison(const std::vector<LabelledSeries>& series, const std::string& path);

// The source drawn over the series' figures: its Pouliquen rule's U at each run's own theta and
// h (result `thickness`), its phi(U) law over [u0, u1], its range of f over [x0, x1].
std::vector<FrictionCurve> source_velocity_points(const SeriesAnalysis& series, const std::string& thickness);
std::vector<FrictionCurve> source_phi_lines(const SourceNumbers& source, double u0, double u1);
std::vector<Curve> source_frequency_range(const SourceNumbers& source, double x0, double x1);

}  // namespace cdpost
