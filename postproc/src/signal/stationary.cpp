#include "signal/stationary.h"

#include <gsl/gsl_fit.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "signal/statistics.h"

namespace cdpost {

double relative_drift(const std::vector<double>& time, const std::vector<double>& signal, const Window& window)
{
  const double* t = time.data() + window.begin;
  const double* s = signal.data() + window.begin;
  double intercept, slope, cov00, cov01, cov11, sumsq;
  gsl_fit_linear(t, 1, s, 1, window.size(), &intercept, &slope, &cov00, &cov01, &cov11, &sumsq);
  double drift = std::abs(slope) * (time[window.end - 1] - time[window.begin]);
  double scale = std::max(std::abs(gsl_stats_mean(s, 1, window.size())), gsl_stats_sd(s, 1, window.size()));
  return scale > 0 ? drift / scale : 0.0;
}

Window detect_stationary(const std::vector<double>& time, const std::vector<double>& signal,
                         const StationaryCriterion& criterion)
{
  const size_t n = signal.size();
  if (n < 20 || time.size() != n) throw AnalysisError("too few samples to detect a stationary regime");
  const size_t min_length = std::max<size_t>(10, static_cast<size_t>(criterion.min_window_fraction * n));
  const size_t last_start = n - min_length;
  const int candidates = std::max(1, criterion.candidate_starts);
  double best_drift = INFINITY;
  for (int c = 0; c < candidates; ++c) {
    Window window{last_start * static_cast<size_t>(c) / static_cast<size_t>(candidates), n};
    double drift = relative_drift(time, signal, window);
    if (drift <= criterion.max_relative_drift) return window;
    best_drift = std::min(best_drift, drift);
  }
  std::ostringstream message;
  message << "no stationary regime: the smallest relative drift over windows of at least "
          << criterion.min_window_fraction * 100 << "% of the run is " << best_drift << " (limit "
          << criterion.max_relative_drift << "); run longer, or override with --t-start/--max-drift";
  throw AnalysisError(message.str());
}

Window window_between(const std::vector<double>& time, double t_start, double t_end)
{
  Window window;
  window.begin = static_cast<size_t>(std::lower_bound(time.begin(), time.end(), t_start) - time.begin());
  window.end = static_cast<size_t>(std::upper_bound(time.begin(), time.end(), t_end) - time.begin());
  if (window.end <= window.begin + 1) {
    std::ostringstream message;
    message << "the window from t = " << t_start << " s to " << t_end << " s holds fewer than 2 samples (the run's "
            << time.size() << " samples span " << (time.empty() ? 0.0 : time.front()) << " s to "
            << (time.empty() ? 0.0 : time.back()) << " s)";
    throw AnalysisError(message.str());
  }
  return window;
}

}  // namespace cdpost
