#include "signal/space_time.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "signal/fft.h"
#include "signal/statistics.h"

namespace cdpost {

namespace {

using Complex = std::complex<double>;
// transforms[j][l]: the tapered segment of column j, transformed (l = 0 .. N/2).
using ColumnTransforms = std::vector<std::vector<Complex>>;

WelchSegments checked_segments(const SpaceTimeField& field, const SpectrumOptions& options)
{
  if (field.columns.empty()) throw AnalysisError("v(x, t) has no column");
  if (!(field.cell_length > 0)) throw AnalysisError("the cell length must be positive");
  const size_t samples = field.columns.front().size();
  for (size_t j = 0; j < field.columns.size(); ++j)
    if (field.columns[j].size() != samples)
      throw AnalysisError("column " + std::to_string(j + 1) + " has " + std::to_string(field.columns[j].size()) +
                          " samples, column 1 has " + std::to_string(samples));
  return welch_segments(samples, field.sample_interval_s, options);
}

// Calls visit(transforms) once per Welch segment.
template <class Visit>
void for_each_segment(const SpaceTimeField& field, const WelchSegments& cut, const SegmentTaper& taper, Visit visit)
{
  RealTransform transform(cut.length);
  ColumnTransforms transforms(field.columns.size(), std::vector<Complex>(transform.bins()));
  for (size_t segment = 0; segment < cut.count; ++segment) {
    for (size_t j = 0; j < field.columns.size(); ++j) {
      taper.apply(field.columns[j].data() + segment * cut.step, transform.input());
      transform.execute();
      for (size_t l = 0; l < transform.bins(); ++l) transforms[j][l] = transform.value(l);
    }
    visit(transforms);
  }
}

// |sum_n w_n w_{n+shift} exp(-2 pi i d n / N)| / sum_n w_n^2: the correlation of the transforms
// of white noise between two segments `shift` samples apart (d = 0), or between two bins d apart
// in one segment (shift = 0).
double window_correlation(const std::vector<double>& w, size_t shift, size_t bin_distance)
{
  const size_t n = w.size();
  Complex sum = 0;
  double norm = 0;
  for (size_t i = 0; i < n; ++i) {
    norm += w[i] * w[i];
    if (i + shift < n) sum += w[i] * w[i + shift] * std::polar(1.0, -2 * M_PI * double(bin_distance * i) / double(n));
  }
  return std::abs(sum) / norm;
}

// (sum_a p_a)^2 / sum_{a,b} p_a p_b rho(|a - b|)^2: the effective number of independent terms in
// a sum of terms of powers p_a (segments, or the bins of a band) whose correlation at distance d
// is correlation(d); n for n uncorrelated terms of equal power.
template <class Correlation>
double effective_count(const std::vector<double>& p, Correlation correlation)
{
  const size_t n = p.size();
  std::vector<double> rho(n);
  for (size_t d = 0; d < n; ++d) rho[d] = correlation(d);
  double total = 0, sum = 0;
  for (size_t a = 0; a < n; ++a) {
    total += p[a];
    for (size_t b = 0; b < n; ++b) sum += p[a] * p[b] * std::pow(rho[a > b ? a - b : b - a], 2);
  }
  return total * total / sum;
}

using CrossSpectra = std::vector<Complex>;  // [j * M + k], k >= j
constexpr size_t kJackknifeGroups = 10;

// The mean over the column pairs at each periodic distance s = 1 .. M/2 of |S_jk|^2 / (S_jj S_kk).
std::vector<double> mean_coherence_by_distance(const CrossSpectra& cross, size_t columns)
{
  std::vector<double> coherence;
  for (size_t s = 1; s <= columns / 2; ++s) {
    double sum = 0;
    for (size_t j = 0; j < columns; ++j) {  // at s = M/2 each pair is met twice: the mean is unchanged
      const size_t a = std::min(j, (j + s) % columns), b = std::max(j, (j + s) % columns);
      sum += std::norm(cross[a * columns + b]) / (cross[a * columns + a].real() * cross[b * columns + b].real());
    }
    coherence.push_back(sum / double(columns));
  }
  return coherence;
}

}  // namespace

double SpaceTimeSpectrum::power_at(int m, size_t l) const
{
  const int p = ((m % columns) + columns) % columns;
  return power[static_cast<size_t>(p) * bins + l];
}

double SpaceTimeSpectrum::wavenumber(int m) const
{
  return 2 * M_PI * m / cell_length;
}

SpaceTimeSpectrum space_time_spectrum(const SpaceTimeField& field, const SpectrumOptions& options)
{
  const auto cut = checked_segments(field, options);
  const SegmentTaper taper(cut.length);
  const size_t columns = field.columns.size();
  SpaceTimeSpectrum spectrum;
  spectrum.columns = static_cast<int>(columns);
  spectrum.cell_length = field.cell_length;
  spectrum.bins = cut.length / 2 + 1;
  spectrum.segment_duration_s = cut.length * field.sample_interval_s;
  spectrum.resolution_hz = 1 / spectrum.segment_duration_s;
  spectrum.segments = static_cast<int>(cut.count);
  spectrum.power.assign(columns * spectrum.bins, 0.0);
  // C(p, l) = sum_j X_j(l) exp(+2 pi i p j / M): X_j(l) of the wave cos(2 pi (m x/L - f_l t))
  // carries exp(-2 pi i m j / M), so the sum peaks at p = m mod M.
  std::vector<Complex> in(columns), out(columns);
  fftw_plan plan = fftw_plan_dft_1d(static_cast<int>(columns), reinterpret_cast<fftw_complex*>(in.data()),
                                    reinterpret_cast<fftw_complex*>(out.data()), FFTW_BACKWARD, FFTW_ESTIMATE);
  const std::unique_ptr<fftw_plan_s, PlanDestroy> owned(plan);
  for_each_segment(field, cut, taper, [&](const ColumnTransforms& transforms) {
    for (size_t l = 0; l < spectrum.bins; ++l) {
      for (size_t j = 0; j < columns; ++j) in[j] = transforms[j][l];
      fftw_execute(plan);
      const double scale = one_sided_scale(l, cut.length, taper.window_sum()) / double(columns);
      for (size_t p = 0; p < columns; ++p) spectrum.power[p * spectrum.bins + l] += std::norm(scale * out[p]);
    }
  });
  for (double& p : spectrum.power) p /= spectrum.segments;
  return spectrum;
}

FrequencyBand band_around(double resolution_hz, size_t bins, double frequency_hz, double half_width_hz)
{
  if (bins == 0 || !(resolution_hz > 0)) throw AnalysisError("a frequency band needs a spectrum");
  auto bin_of = [&](double f) { return std::clamp(f / resolution_hz, 0.0, double(bins - 1)); };
  FrequencyBand band;
  band.first = static_cast<size_t>(std::ceil(bin_of(frequency_hz - half_width_hz) - 1e-9));
  band.last = static_cast<size_t>(std::floor(bin_of(frequency_hz + half_width_hz) + 1e-9));
  if (band.last < band.first) band.first = band.last = static_cast<size_t>(std::lround(bin_of(frequency_hz)));
  return band;
}

std::vector<double> band_power_by_m(const SpaceTimeSpectrum& spectrum, const FrequencyBand& band)
{
  std::vector<double> power;
  for (int m = spectrum.lowest_m(); m <= spectrum.highest_m(); ++m) {
    double sum = 0;
    for (size_t l = band.first; l <= band.last; ++l) sum += spectrum.power_at(m, l);
    power.push_back(sum);
  }
  return power;
}

CoherenceByDistance coherence_by_distance(const SpaceTimeField& field, const SpectrumOptions& options,
                                          double frequency_hz, double half_width_hz)
{
  const auto cut = checked_segments(field, options);
  const size_t columns = field.columns.size();
  if (columns < 2) throw AnalysisError("coherence between columns needs at least 2 columns");
  const SegmentTaper taper(cut.length);
  CoherenceByDistance result;
  result.band =
      band_around(1 / (cut.length * field.sample_interval_s), cut.length / 2 + 1, frequency_hz, half_width_hz);
  result.segments = static_cast<int>(cut.count);
  // cross[g][j * M + k]: sum over the segments of group g and the band bins of X_j conj(X_k); the
  // power of all columns per segment and per band bin weighs the effective count of averages.
  const size_t groups = std::min<size_t>(cut.count, kJackknifeGroups);
  std::vector<CrossSpectra> cross(groups, CrossSpectra(columns * columns, 0.0));
  std::vector<double> segment_power, bin_power(result.band.size(), 0.0);
  for_each_segment(field, cut, taper, [&](const ColumnTransforms& x) {
    auto& group = cross[segment_power.size() * groups / cut.count];
    segment_power.push_back(0);
    for (size_t j = 0; j < columns; ++j)
      for (size_t k = j; k < columns; ++k)
        for (size_t l = result.band.first; l <= result.band.last; ++l) {
          const Complex product = x[j][l] * std::conj(x[k][l]);
          group[j * columns + k] += product;
          if (k == j) segment_power.back() += product.real(), bin_power[l - result.band.first] += product.real();
        }
  });
  CrossSpectra total(columns * columns, 0.0);
  for (const auto& group : cross)
    for (size_t i = 0; i < total.size(); ++i) total[i] += group[i];
  for (size_t j = 0; j < columns; ++j)
    if (!(total[j * columns + j].real() > 0))
      throw AnalysisError("column " + std::to_string(j + 1) + " has no power near " + std::to_string(frequency_hz) +
                          " Hz: no coherence can be measured");
  const double width = field.cell_length / double(columns);
  for (size_t s = 1; s <= columns / 2; ++s) {
    result.distance.push_back(double(s) * width);
    result.pairs.push_back(static_cast<int>(2 * s == columns ? columns / 2 : columns));
  }
  result.coherence = mean_coherence_by_distance(total, columns);
  if (groups > 1)
    for (const auto& group : cross) {
      CrossSpectra rest(total);
      for (size_t i = 0; i < rest.size(); ++i) rest[i] -= group[i];
      result.without_group.push_back(mean_coherence_by_distance(rest, columns));
    }
  const auto& w = taper.window();
  result.averages = effective_count(segment_power, [&](size_t d) { return window_correlation(w, d * cut.step, 0); }) *
                    effective_count(bin_power, [&](size_t d) { return window_correlation(w, 0, d); });
  result.noise_floor = 1 / result.averages;
  return result;
}

}  // namespace cdpost
