// Where the oscillation lives along the cell: from v(x, t) of the flowing layer in columns
// tiling the periodic cell (columns.chunk), the space–time spectrum, the coherence of v between
// columns against their distance at the layer's peak frequency, the coherence length, and a
// verdict: uniform, standing, travelling or local (doc/postproc.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fit/linear_fit.h"
#include "io/ave_chunk.h"
#include "output/results.h"
#include "signal/space_time.h"

namespace cdpost {

// The codes are written to results.csv (oscillation_pattern), so that a published run keeps them.
enum class OscillationPattern { Uniform = 1, Standing = 2, Travelling = 3, Local = 4 };
std::string pattern_name(OscillationPattern pattern);
// The name of a code read back from results.csv; nothing for an unknown code.
std::optional<std::string> pattern_name(double code);

// v(x, t) from the blocks of a columns.chunk file: column v_column times velocity_factor, the
// cell length in d. A column empty (count 0) in a sample takes the value interpolated in time
// between its nearest occupied samples (`filled` counts them). Throws AnalysisError when the
// columns do not tile the cell (Coord1 = (j + 1/2)/M, reduced units), when there are fewer
// than 8 (4 distances for the coherence fit) or when a column is empty in more than 5 % of the
// samples (too sparse for interpolation to be harmless: widen column_width).
struct ColumnsLayout {
  size_t coord = 0, v = 0, count = 0;  // column indices in the chunk file
};
SpaceTimeField field_from_chunks(const ChunkSeries& chunks, const std::vector<size_t>& blocks,
                                 const ColumnsLayout& layout, double velocity_factor, double sample_interval_s,
                                 double cell_length_d, size_t& filled);

// C(r) = gamma(r)^2, gamma(r) = g_far + (g0 - g_far) exp(-r / xi): the coherence of a field
// whose correlation at f is a part coherent across the whole cell (a uniform or standing
// oscillation: the plateau C = g_far^2) plus a part decaying as exp(-r / xi) (for a pure
// exponential, C = exp(-2 r / xi)). c0 = g0^2 < 1 when each column carries noise of its own.
// The coherencies are magnitudes, 0 <= g0, g_far <= 1 (fitted through angles, g = sin^2 a), so
// c0 and the plateau never exceed 1. Fitted as the expected estimate from n averages,
// C + (1 - C)^2 / n (the noise floor 1/n where C vanishes). 1/xi is fitted, so that no decay is a
// value like any other. xi is given only when 1/xi exceeds twice its error and the coherence
// decays over the measured distances (coherence_decays). The errors are the jackknife's over the
// groups of segments (CoherenceByDistance::without_group): every distance is measured on the same
// segments, so the scatter about the fit underestimates them.
struct CoherenceFit {
  Estimate short_range;            // c0, the coherence extrapolated to r = 0
  Estimate plateau;                // g_far^2, the coherence left at every distance
  Estimate inverse_length;         // 1/xi, 1/d
  std::optional<Estimate> length;  // xi, d
  double g0 = 0, g_far = 0;        // the fitted coherencies
  FitResult raw;                   // g0_angle, g_far_angle, inverse_length
};
CoherenceFit fit_coherence(const CoherenceByDistance& coherence);  // needs 4 distances, 3 groups

// The measured coherence at the first distance minus at the last, with its jackknife error
// (needs 2 groups). The coherence decays when that exceeds twice its error and the noise floor
// (the coherence incoherent columns read: a smaller decay is not resolved by the estimate). A
// decay before the first distance is not measured: the fit's extrapolation to r = 0 is no decay.
Estimate coherence_decay(const CoherenceByDistance& coherence);
bool coherence_decays(const CoherenceByDistance& coherence);
double fitted_coherence(const CoherenceFit& fit, double floor, double distance);  // the expected estimate

struct PatternVerdict {
  OscillationPattern pattern = OscillationPattern::Uniform;
  double uniform_fraction = 0;  // share of the band's power at m = 0
  int dominant_m = 0;           // the |m| >= 1 with most band power, signed by its stronger direction
  Estimate balance;             // (P(+m) - P(-m)) / (P(+m) + P(-m)) at |dominant_m|
  std::string text;             // the verdict with its numbers, one line
};
// The verdict, in this order: local when neighbouring columns are no more coherent than twice
// the noise floor, or when xi + 2 sigma < L/2 and the plateau is below half the neighbours'
// coherence (the two halves of the cell oscillate nearly independently); else uniform when m = 0 holds at least half the power at f; else travelling
// when one direction of the dominant |m| holds at least twice the power of the other (|balance|
// >= 1/3, and beyond twice its error), standing otherwise. band_power as band_power_by_m gives
// it for `columns` columns; the balance's error (1 - b^2) / sqrt(2 n) with n the coherence's
// averages (each P(+-m) a mean of n squared Gaussian amplitudes). With fewer than 4 averages
// the coherence tells nothing (one segment reads 1): never local then, the wavenumbers alone
// judge, and the text says the coherence does not resolve the pattern.
PatternVerdict judge_pattern(const std::vector<double>& band_power, int columns, const CoherenceByDistance& coherence,
                             const std::optional<CoherenceFit>& fit, double cell_length_d);

struct AlongCell {
  SpaceTimeSpectrum spectrum;       // v in sqrt(g d), lengths in d
  CoherenceByDistance coherence;    // distances in d
  std::optional<Estimate> decay;    // coherence_decay, when the window has 3 groups of segments
  std::optional<CoherenceFit> fit;  // absent when it could not be made, for no_fit_reason
  std::string no_fit_reason;
  std::vector<double> band_power;  // per m, as band_power_by_m
  PatternVerdict verdict;
  double frequency_hz = 0;                 // the layer's peak frequency
  std::optional<Estimate> phase_velocity;  // f L / m, sqrt(g d), > 0 along +x; when travelling
};

// The analysis of v(x, t) (v in sqrt(g d), cell length in d) at the layer's spectral peak;
// its numbers go to `results`, a failed coherence fit to `warnings`. reduced_rate_hz = sqrt(g/d).
AlongCell analyse_along_cell(const SpaceTimeField& field, const SpectralPeak& peak, const SpectrumOptions& options,
                             double reduced_rate_hz, ResultTable& results, std::vector<std::string>& warnings);

}  // namespace cdpost
