#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "signal/spectrum.h"

namespace cdpost {
namespace {

// a sin(2 pi f t) + Gaussian noise of standard deviation `noise`, sampled every dt.
std::vector<double> tone(double amplitude, double frequency_hz, double noise, double duration_s, double dt,
                         unsigned seed = 1)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  std::vector<double> signal;
  for (double t = 0; t < duration_s; t += dt)
    signal.push_back(amplitude * std::sin(2 * M_PI * frequency_hz * t + 0.3) + (noise > 0 ? gauss(rng) : 0.0));
  return signal;
}

TEST(Spectrum, PureToneOnABinReadsItsAmplitudeAndFrequency)
{
  auto spectrum = amplitude_spectrum(tone(0.7, 40.0, 0.0, 4.0, 1e-3), 1e-3, {});
  EXPECT_DOUBLE_EQ(spectrum.resolution_hz, 1.0);
  EXPECT_EQ(spectrum.segments, 7);
  auto peak = find_peak(spectrum, 5, 400);
  EXPECT_NEAR(peak.amplitude, 0.7, 1e-6);
  EXPECT_NEAR(peak.frequency_hz, 40.0, 1e-6);
  // Hann: neighbours of a centred tone read half the peak, so the interpolated half-power
  // crossing lies (1 - 1/sqrt(2)) / 0.5 = 0.586 bins out.
  EXPECT_NEAR(peak.frequency_error_hz, 0.586, 0.01);
}

TEST(Spectrum, NoisyToneRecoversFrequencyWithinItsErrorBar)
{
  std::mt19937 seeds(7);
  for (double f : {23.3, 61.7, 137.2}) {
    auto spectrum = amplitude_spectrum(tone(0.5, f, 1.0, 8.0, 1e-3, seeds()), 1e-3, {});
    auto peak = find_peak(spectrum, 5, 400);
    EXPECT_NEAR(peak.frequency_hz, f, peak.frequency_error_hz) << f;
    EXPECT_NEAR(peak.amplitude, 0.5, 0.5 * 0.2) << f;  // scalloping (<15%) + noise
  }
}

TEST(Spectrum, AmplitudeIsComparableBetweenRunsOfDifferentLengths)
{
  auto short_run = amplitude_spectrum(tone(0.3, 50, 0.5, 3.0, 1e-3, 3), 1e-3, {});
  auto long_run = amplitude_spectrum(tone(0.3, 50, 0.5, 12.0, 1e-3, 4), 1e-3, {});
  EXPECT_NEAR(find_peak(short_run, 5, 400).amplitude, find_peak(long_run, 5, 400).amplitude, 0.06);
  EXPECT_NEAR(mean_amplitude_above(short_run, 100), mean_amplitude_above(long_run, 100),
              0.1 * mean_amplitude_above(long_run, 100));
}

TEST(Spectrum, WhiteNoiseLevelMatchesTheNormalisation)
{
  // For white noise of variance s^2 and a Hann window, <a_k^2> = 4 s^2 sum(w^2)/sum(w)^2 = 6 s^2 / N.
  const double dt = 1e-3, sigma = 2.0;
  auto spectrum = amplitude_spectrum(tone(0, 1, sigma, 20.0, dt, 11), dt, {});
  const double n = 1.0 / dt;
  double rms = 0;
  int count = 0;
  for (size_t k = 100; k < spectrum.amplitude.size() - 1; ++k, ++count)
    rms += spectrum.amplitude[k] * spectrum.amplitude[k];
  EXPECT_NEAR(std::sqrt(rms / count), std::sqrt(6.0 / n) * sigma, 0.05 * std::sqrt(6.0 / n) * sigma);
}

TEST(Spectrum, ResonancePeakErrorBarIsItsHalfWidth)
{
  // Noise driving a damped oscillator (AR(2) process): a Lorentzian peak at 40 Hz whose
  // half width at half power is damping / (2 pi) = 3 Hz.
  const double dt = 1e-3, f0 = 40, damping = 2 * M_PI * 3;
  const double r = std::exp(-damping * dt), c1 = 2 * r * std::cos(2 * M_PI * f0 * dt), c2 = -r * r;
  std::mt19937 rng(13);
  std::normal_distribution<double> kick(0, 1);
  std::vector<double> signal{0, 0};
  for (int i = 0; i < 40000; ++i) signal.push_back(c1 * signal.back() + c2 * signal[signal.size() - 2] + kick(rng));
  auto peak = find_peak(amplitude_spectrum(signal, dt, {}), 5, 400);
  EXPECT_NEAR(peak.frequency_hz, f0, peak.frequency_error_hz);
  EXPECT_NEAR(peak.frequency_error_hz, 3.0, 1.0);
}

TEST(Spectrum, ShortSignalIsOneSegmentAndBadInputsThrow)
{
  auto spectrum = amplitude_spectrum(tone(1, 100, 0, 0.2, 1e-3), 1e-3, {});
  EXPECT_EQ(spectrum.segments, 1);
  EXPECT_NEAR(spectrum.resolution_hz, 5.0, 1e-9);
  EXPECT_THROW(amplitude_spectrum(std::vector<double>(5, 1.0), 1e-3, {}), std::runtime_error);
  EXPECT_THROW(mean_amplitude_above(spectrum, 1000), std::runtime_error);
  EXPECT_THROW(find_peak(spectrum, 600, 700), std::runtime_error);
}

}  // namespace
}  // namespace cdpost
