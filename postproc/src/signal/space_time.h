// v(x, t) on columns tiling a periodic cell: its space–time power spectrum and the coherence
// of v between columns against their distance.
//
// Columns j = 0 .. M-1 of width w = L/M (column j centred at (j + 1/2) w), sampled every dt.
// Time is cut into Welch segments as amplitude_spectrum cuts a signal (segment duration and
// overlap of SpectrumOptions; each column's segment detrended and Hann-windowed); x is periodic
// and needs no window. Sign convention: at f > 0, m > 0 is a wave cos(2 pi (m x / L - f t))
// travelling along +x, m < 0 one travelling along -x.
#pragma once

#include <vector>

#include "signal/spectrum.h"

namespace cdpost {

struct SpaceTimeField {
  std::vector<std::vector<double>> columns;  // columns[j][n]: v of column j at sample n (any unit)
  double sample_interval_s = 0;
  double cell_length = 0;  // L (any length unit: distances and wavenumbers come out in it)
};

struct SpaceTimeSpectrum {
  int columns = 0;           // M
  double cell_length = 0;    // L
  size_t bins = 0;           // frequency bins l = 0 .. N/2
  double resolution_hz = 0;  // f_l = l * resolution_hz
  double segment_duration_s = 0;
  int segments = 0;
  std::vector<double> power;  // power[p * bins + l], p = m mod M (see power_at)

  // Mean over the segments of a^2 for the component a cos(2 pi (m x / L - f_l t) + phase):
  // such a wave centred on bin l reads a^2; a uniform oscillation a cos(2 pi f t) reads a^2 at
  // m = 0 (its spectral amplitude, as amplitude_spectrum gives it, squared). Units: v^2.
  double power_at(int m, size_t l) const;
  // m runs over -M/2 .. M/2 (integer division); for even M, -M/2 and M/2 are the same bin
  // (its direction cannot be told).
  int highest_m() const { return columns / 2; }
  int lowest_m() const { return -(columns / 2); }
  double wavenumber(int m) const;  // 2 pi m / L
  double frequency_hz(size_t l) const { return static_cast<double>(l) * resolution_hz; }
};

// Throws AnalysisError for no column, columns of unequal length, L <= 0 or too few samples.
SpaceTimeSpectrum space_time_spectrum(const SpaceTimeField& field, const SpectrumOptions& options);

// The frequency bins within half_width_hz of frequency_hz, at least the nearest one.
struct FrequencyBand {
  size_t first = 0, last = 0;  // inclusive
  size_t size() const { return last - first + 1; }
};
FrequencyBand band_around(double resolution_hz, size_t bins, double frequency_hz, double half_width_hz);

// power_at(m, l) summed over the band's bins, for m = lowest_m() .. highest_m() (index m - lowest_m()).
std::vector<double> band_power_by_m(const SpaceTimeSpectrum& spectrum, const FrequencyBand& band);

// Magnitude-squared coherence C = |S_jk|^2 / (S_jj S_kk) of each column pair, from the cross
// spectra S summed over the Welch segments and the band's bins, averaged over the pairs at
// each periodic distance r = s w, s = 1 .. M/2.
struct CoherenceByDistance {
  std::vector<double> distance;   // r, cell-length units
  std::vector<double> coherence;  // mean C of the pairs at r
  std::vector<int> pairs;         // distinct column pairs at r
  FrequencyBand band;
  int segments = 0;
  // Effective independent averages in each cross spectrum: segments times band bins, each
  // counted as (sum_a p_a)^2 / sum_ab p_a p_b rho_ab^2 with p the columns' power in segment or
  // bin a and rho the Hann window's correlation of overlapping segments or neighbouring bins.
  double averages = 0;
  double noise_floor = 0;  // 1 / averages: the expected C of incoherent columns
  // Jackknife: the segments cut into up to 10 contiguous groups; without_group[g] is the
  // coherence against distance with group g left out (its noise floor noise_floor G / (G - 1)).
  std::vector<std::vector<double>> without_group;
};
// Needs at least 2 columns; throws AnalysisError naming a column with no power in the band.
CoherenceByDistance coherence_by_distance(const SpaceTimeField& field, const SpectrumOptions& options,
                                          double frequency_hz, double half_width_hz);

}  // namespace cdpost
