// Amplitude spectrum of a sampled signal (FFTW), its peak and its high-frequency level.
//
// Method (Welch): the signal is cut into segments of fixed duration `segment_duration_s`
// overlapping by `overlap`; each segment has its least-squares line removed and is
// multiplied by a periodic Hann window; the one-sided amplitude of bin k is
// a_k = 2 |X_k| / sum(w) (|X_k| / sum(w) at 0 and Nyquist), so that a sinusoid of
// amplitude a centred on a bin reads a. The spectrum is the root-mean-square of a_k over
// the segments. Because the segment duration is fixed, a run twice as long averages more
// segments but keeps the same resolution and amplitude scale: runs of different lengths
// (and equal sampling interval) are comparable. A signal shorter than one segment is
// analysed as a single segment of its own length.
#pragma once

#include <cstddef>
#include <vector>

namespace cdpost {

struct SpectrumOptions {
  double segment_duration_s = 1.0;
  double overlap = 0.5;  // fraction of a segment shared with the next
};

struct Spectrum {
  std::vector<double> frequency_hz;
  std::vector<double> amplitude;  // units of the signal
  double resolution_hz = 0;
  int segments = 0;
  double segment_duration_s = 0;
};

Spectrum amplitude_spectrum(const std::vector<double>& signal, double sample_interval_s,
                            const SpectrumOptions& options);

// The Welch segmentation of `samples` samples (as amplitude_spectrum cuts them): segment
// `length` samples, starts `step` apart, `count` segments. Throws AnalysisError for fewer than
// 16 samples, a non-positive interval or an overlap outside [0, 1).
struct WelchSegments {
  size_t length = 0, step = 0, count = 0;
};
WelchSegments welch_segments(size_t samples, double sample_interval_s, const SpectrumOptions& options);

// A segment's preparation: its least-squares line removed, times a periodic Hann window.
class SegmentTaper {
 public:
  explicit SegmentTaper(size_t length);
  void apply(const double* segment, double* out) const;  // `length` values each
  const std::vector<double>& window() const { return window_; }
  double window_sum() const { return window_sum_; }

 private:
  std::vector<double> window_, sample_index_;
  double window_sum_ = 0;
};

// The factor turning |X_k| of an n-point transform of a tapered segment into the one-sided
// amplitude of bin k: 2 / sum(w), and 1 / sum(w) at 0 and at Nyquist.
double one_sided_scale(size_t k, size_t n, double window_sum);

// The highest amplitude in [fmin_hz, fmax_hz]. frequency_hz is refined by a parabola
// through the maximum and its neighbours; frequency_error_hz is the half width at half
// maximum of the peak in power (amplitude falls to peak/sqrt(2)), found by linear
// interpolation between bins and never less than half the resolution.
struct SpectralPeak {
  double frequency_hz = 0;
  double frequency_error_hz = 0;
  double amplitude = 0;  // the maximal bin's amplitude
};
SpectralPeak find_peak(const Spectrum& spectrum, double fmin_hz, double fmax_hz);

// Mean amplitude over the bins with f >= fmin_hz (A_mean). Throws if there is none.
double mean_amplitude_above(const Spectrum& spectrum, double fmin_hz);

// Amplitude at the bin nearest to `frequency_hz`.
double amplitude_at(const Spectrum& spectrum, double frequency_hz);

}  // namespace cdpost
