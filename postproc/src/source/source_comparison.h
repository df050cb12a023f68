// A series against the numbers of its source (source/source_numbers.h): curves compared as
// curves (each run against the source's rule at the run's own I, h and U), ranges as ranges,
// signs as signs with their errors; the fit parameters that the runs cannot separate (3
// parameters over a few angles) shown apart as degenerate, with their correlation; and the
// source's own two flow rules checked against each other.
#pragma once

#include <string>
#include <vector>

#include "analysis/series_analysis.h"
#include "output/gnuplot.h"
#include "output/report.h"

namespace cdpost {

// Set by construction: the runs were made to have the source's value (the layer reading's h).
enum class Verdict { Agrees, Outside, NotATarget, Shown, ByConstruction };
// A quantity compared with a tolerance, or a sign (a trend's direction beyond its errors).
enum class RowKind { Quantity, Sign };

// One comparison of a series with its source.
struct SourceRow {
  std::string key;        // the source row compared (source.csv's name, with the friction's suffix)
  std::string quantity;   // what is compared
  std::string source;     // the source's number
  std::string tolerance;  // what counts as agreeing
  std::string ours;       // the series' reading
  Verdict verdict = Verdict::Shown;
  RowKind kind = RowKind::Quantity;
};
// "agrees", "outside", ..., a sign's "sign agrees" and "sign differs": the tally of a table
// (source_comparison.csv's readers too) counts quantities apart from signs by these words.
std::string verdict_text(const SourceRow& row);

// The rows grouped as the table shows them: quantities, then signs, then those set by
// construction or only shown (angles run), each group in the order compared.
std::vector<SourceRow> grouped(std::vector<SourceRow> rows);

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

// Each run against both of the source's flow rules under each reading of its I: the report's
// table "The source's flow rules under each I" and OUT/inertial_readings.csv
// (run,mu,theta_deg,reading,I,I_error,theta_minus_pouliquen_deg,theta_minus_muI_deg).
void inertial_readings_section(MarkdownReport& report, const SeriesAnalysis& series);
void write_inertial_readings(const SeriesAnalysis& series, const std::string& path);

// The source drawn over the series' figures: its Pouliquen rule's U at each run's own theta and
// h (result `thickness`), its phi(U) law over [u0, u1], its range of f over [x0, x1].
std::vector<FrictionCurve> source_velocity_points(const SeriesAnalysis& series, const std::string& thickness);
std::vector<FrictionCurve> source_phi_lines(const SourceNumbers& source, double u0, double u1);
std::vector<Curve> source_frequency_range(const SourceNumbers& source, double x0, double x1);
// Both of the source's flow rules as theta (deg) against I over [i0, i1]: Pouliquen's dashed, the
// mu(I) rule's solid, a pair per friction.
std::vector<FrictionCurve> source_rule_curves(const SourceNumbers& source, double i0, double i1);

}  // namespace cdpost
