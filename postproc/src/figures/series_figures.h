// The outputs of a series (analysis/series_analysis.h), and the pieces of its figures shared with
// the comparison of two series (series_comparison_figures.cpp): the runs' points and the fitted
// curves, each tagged with its friction.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "analysis/series_analysis.h"
#include "output/gnuplot.h"
#include "output/report.h"

namespace cdpost {

// OUT/runs.csv (one row per flowing run), OUT/fits.{csv,json}, OUT/residuals.csv, OUT/held_fits.csv,
// OUT/layer_amplitudes.csv, OUT/depth_decay.csv, OUT/figures, OUT/report.md.
void write_series_outputs(SeriesAnalysis& series, const std::string& out_dir);

// A section `heading` with each run's solver health (analysis/solver_health.h), "not recorded"
// where the run's solver.time was absent (or, for a published run, its results hold none).
void solver_section(MarkdownReport& report, const SeriesAnalysis& series, const std::string& heading);

// Result y (with its error bars if any) against result x ("theta": the tilt), one curve per
// friction coefficient that has runs with both.
std::vector<FrictionCurve> points_by_friction(const SeriesAnalysis& series, const std::string& x, const std::string& y);

// The fitted curves, each with its band of one standard error (delta method, fit covariance).
// U/sqrt(g d) against theta (deg) of Pouliquen's rule (beta fixed) and of the mu(I) rule under
// `fits`, drawn at each friction's mean thickness and up to u_max (both diverge at theta2):
std::vector<FrictionCurve> pouliquen_curves(const SeriesAnalysis& series, const DefinitionFits& fits, double u_max);
std::vector<FrictionCurve> mu_of_i_curves(const SeriesAnalysis& series, const DefinitionFits& fits, double u_max);
// phi = phi_c(mu) - k x of a linear phi law, over [x0, x1]:
std::vector<FrictionCurve> phi_law_curves(const PhiFit& law, double x0, double x1);
// f = c x^n over [x0, x1], one curve for every friction:
Curve power_law_curve(const PowerLaw& law, double x0, double x1);

// The smallest and largest x of the curves' points.
std::pair<double, double> x_extent(const std::vector<Curve>& curves);

}  // namespace cdpost
