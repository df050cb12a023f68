#include "signal/spectrum.h"

#include <gsl/gsl_fit.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "signal/fft.h"
#include "signal/statistics.h"

namespace cdpost {

SegmentTaper::SegmentTaper(size_t length) : window_(length), sample_index_(length)
{
  for (size_t i = 0; i < length; ++i) {
    window_[i] = 0.5 * (1.0 - std::cos(2.0 * M_PI * i / length));
    window_sum_ += window_[i];
    sample_index_[i] = static_cast<double>(i);
  }
}

void SegmentTaper::apply(const double* segment, double* out) const
{
  const size_t n = window_.size();
  double intercept, slope, cov00, cov01, cov11, sumsq;
  gsl_fit_linear(sample_index_.data(), 1, segment, 1, n, &intercept, &slope, &cov00, &cov01, &cov11, &sumsq);
  for (size_t i = 0; i < n; ++i) out[i] = window_[i] * (segment[i] - intercept - slope * sample_index_[i]);
}

double one_sided_scale(size_t k, size_t n, double window_sum)
{
  const bool edge = (k == 0) || (n % 2 == 0 && k == n / 2);
  return (edge ? 1.0 : 2.0) / window_sum;
}

WelchSegments welch_segments(size_t samples, double sample_interval_s, const SpectrumOptions& options)
{
  if (samples < 16) throw AnalysisError("a spectrum needs at least 16 samples, got " + std::to_string(samples));
  if (!(sample_interval_s > 0)) throw AnalysisError("the sample interval must be positive");
  if (!(options.overlap >= 0 && options.overlap < 1)) throw AnalysisError("the segment overlap must be in [0, 1)");
  WelchSegments segments;
  const auto wanted = static_cast<size_t>(std::lround(options.segment_duration_s / sample_interval_s));
  segments.length = std::min(samples, std::max<size_t>(wanted, 8));
  segments.step = std::max<size_t>(1, static_cast<size_t>(std::lround(segments.length * (1.0 - options.overlap))));
  segments.count = (samples - segments.length) / segments.step + 1;
  return segments;
}

Spectrum amplitude_spectrum(const std::vector<double>& signal, double sample_interval_s, const SpectrumOptions& options)
{
  const auto cut = welch_segments(signal.size(), sample_interval_s, options);
  const size_t n = cut.length;
  const SegmentTaper taper(n);
  RealTransform transform(n);
  std::vector<double> power(transform.bins(), 0.0);
  for (size_t segment = 0; segment < cut.count; ++segment) {
    taper.apply(signal.data() + segment * cut.step, transform.input());
    transform.execute();
    for (size_t k = 0; k < power.size(); ++k) {
      const double a = one_sided_scale(k, n, taper.window_sum()) * transform.magnitude(k);
      power[k] += a * a;
    }
  }

  Spectrum spectrum;
  spectrum.segments = static_cast<int>(cut.count);
  spectrum.segment_duration_s = n * sample_interval_s;
  spectrum.resolution_hz = 1.0 / spectrum.segment_duration_s;
  for (size_t k = 0; k < power.size(); ++k) {
    spectrum.frequency_hz.push_back(k * spectrum.resolution_hz);
    spectrum.amplitude.push_back(std::sqrt(power[k] / spectrum.segments));
  }
  return spectrum;
}

namespace {

// Frequency where the amplitude first falls below `level` walking from `peak` by `direction`,
// interpolated between bins; the band edge if it never does.
double crossing(const Spectrum& s, size_t peak, int direction, double level, size_t lo, size_t hi)
{
  size_t k = peak;
  while (true) {
    size_t next = direction > 0 ? k + 1 : k - 1;
    if ((direction > 0 && next > hi) || (direction < 0 && (k == 0 || next < lo))) return s.frequency_hz[k];
    if (s.amplitude[next] < level) {
      double fraction = (s.amplitude[k] - level) / (s.amplitude[k] - s.amplitude[next]);
      return s.frequency_hz[k] + fraction * (s.frequency_hz[next] - s.frequency_hz[k]);
    }
    k = next;
  }
}

double parabolic_offset(double left, double centre, double right)
{
  double curvature = left - 2 * centre + right;
  return curvature < 0 ? 0.5 * (left - right) / curvature : 0.0;
}

}  // namespace

SpectralPeak find_peak(const Spectrum& spectrum, double fmin_hz, double fmax_hz)
{
  const auto& f = spectrum.frequency_hz;
  size_t lo = static_cast<size_t>(std::lower_bound(f.begin(), f.end(), std::max(fmin_hz, 1e-300)) - f.begin());
  size_t hi = static_cast<size_t>(std::upper_bound(f.begin(), f.end(), fmax_hz) - f.begin());
  if (hi <= lo)
    throw AnalysisError("no spectral bin between " + std::to_string(fmin_hz) + " and " + std::to_string(fmax_hz) +
                        " Hz (resolution " + std::to_string(spectrum.resolution_hz) + " Hz)");
  --hi;  // last bin inside the band
  const auto& a = spectrum.amplitude;
  size_t k = static_cast<size_t>(std::max_element(a.begin() + lo, a.begin() + hi + 1) - a.begin());
  SpectralPeak peak;
  peak.amplitude = a[k];
  peak.frequency_hz = f[k];
  if (k > 0 && k + 1 < a.size())
    peak.frequency_hz += parabolic_offset(a[k - 1], a[k], a[k + 1]) * spectrum.resolution_hz;
  const double half_power = a[k] / std::sqrt(2.0);
  double width = crossing(spectrum, k, +1, half_power, lo, hi) - crossing(spectrum, k, -1, half_power, lo, hi);
  peak.frequency_error_hz = std::max(0.5 * width, 0.5 * spectrum.resolution_hz);
  return peak;
}

double mean_amplitude_above(const Spectrum& spectrum, double fmin_hz)
{
  double sum = 0;
  int count = 0;
  for (size_t k = 0; k < spectrum.frequency_hz.size(); ++k)
    if (spectrum.frequency_hz[k] >= fmin_hz) {
      sum += spectrum.amplitude[k];
      ++count;
    }
  if (count == 0)
    throw AnalysisError("no spectral bin at or above " + std::to_string(fmin_hz) +
                        " Hz: sample v(t) more finely (Nyquist " + std::to_string(spectrum.frequency_hz.back()) +
                        " Hz)");
  return sum / count;
}

double amplitude_at(const Spectrum& spectrum, double frequency_hz)
{
  auto k = static_cast<size_t>(std::lround(frequency_hz / spectrum.resolution_hz));
  return spectrum.amplitude[std::min(k, spectrum.amplitude.size() - 1)];
}

}  // namespace cdpost
