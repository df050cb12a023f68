// Detection of the stationary regime of a run from a time series (by default U(t)).
//
// Criterion: the regime starts at the earliest candidate time t_s for which the straight
// line fitted to the signal over [t_s, t_end] drifts by at most `max_relative_drift` times
// the signal's scale (|mean|, or its standard deviation if larger) across that window, and
// the window covers at least `min_window_fraction` of the run. Candidates are evenly spaced.
#pragma once

#include <cstddef>
#include <vector>

namespace cdpost {

struct StationaryCriterion {
  double max_relative_drift = 0.02;
  double min_window_fraction = 0.25;
  int candidate_starts = 50;
};

// Sample index range [begin, end).
using std::size_t;

struct Window {
  size_t begin = 0;
  size_t end = 0;
  size_t size() const { return end - begin; }
};

// Throws AnalysisError when no candidate satisfies the criterion.
Window detect_stationary(const std::vector<double>& time, const std::vector<double>& signal,
                         const StationaryCriterion& criterion);

// Drift of the fitted line across [begin, end) relative to the signal's scale.
double relative_drift(const std::vector<double>& time, const std::vector<double>& signal, const Window& window);

// Samples with t_start <= t <= t_end (an explicit override of the detection).
Window window_between(const std::vector<double>& time, double t_start, double t_end);

}  // namespace cdpost
