// The creep of the bed below the wall tops, u(z) = u0 exp(z / lambda) for z < 0, measured only
// where u stands clear of the solver's noise floor (reduced units: z in d, u in sqrt(g d)).
//
// The floor: given (--creep-floor), or estimated from the profile. Walking down from the
// highest bin below z = 0, the decay ends at the first bin whose u is not positive or not
// smaller than the bin above it; the bins from there down to -depth are the deep bed, where u
// is the solver's (it scatters and changes sign), and the floor is the rms of u over them (at
// least kMinFloorBins; an offset of the whole deep bed counts in it).
// The fit range: from the highest bin below z = 0 down to the last bin before u first falls
// below kFloorMultiple times the floor. With fewer than kMinResolvedPoints bins in it, the
// creep is unresolved (a stated verdict, no lambda). Beside the single lambda of the range, the
// local decay length in depth bands of kBandWidthD below z = 0 (a log-linear fit over the
// range's bins in each band holding at least kMinBandPoints).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fit/linear_fit.h"

namespace cdpost {

constexpr double kFloorMultiple = 10;
constexpr int kMinResolvedPoints = 4;
constexpr int kMinFloorBins = 3;
constexpr double kBandWidthD = 3;
constexpr int kMinBandPoints = 3;

struct CreepSettings {
  double depth_d = 30;                  // the bins with -depth_d <= z < 0 are read
  std::optional<double> floor_reduced;  // the floor, sqrt(g d); none: estimated from the profile
};

struct CreepFloor {
  double value = 0;            // sqrt(g d)
  int bins = 0;                // deep-bed bins it is the rms of; 0 when given
  double z_top = 0;            // d: centre of the deep bed's highest bin (estimated only)
  std::string source() const;  // how it was obtained, in words
};

// The local decay length over the band depth_top_d <= -z < depth_bottom_d.
struct CreepBand {
  double depth_top_d = 0, depth_bottom_d = 0;
  Estimate lambda;  // d
  int points = 0;
};

struct CreepMeasure {
  std::optional<CreepFloor> floor;
  int points = 0;                  // bins in the fit range
  double z_high = 0, z_low = 0;    // d: centres of its highest and deepest bins (points > 0)
  std::optional<Estimate> lambda;  // d, when resolved
  std::optional<Estimate> u0;      // sqrt(g d), when resolved
  std::vector<CreepBand> bands;
  std::vector<std::string> band_problems;  // bands with enough points that do not decay
  std::string verdict;                     // "unresolved: ..." when there is no lambda, else empty
};

// z ascending or not, one entry per profile bin. Throws AnalysisError only on a bad setting.
CreepMeasure measure_creep(const std::vector<double>& z, const std::vector<double>& u, const CreepSettings& settings);

// The decay a guide line drawn by eye on a semi-log plot of u below the wall tops follows: the
// first decade of u, where the points stand far above any floor and span the plot's visible
// slope. u0 exp(z/lambda) fitted over the bins from the highest below z = 0 down to the last
// before u first falls below a tenth of that bin's u or stops decaying (at least kMinBandPoints
// bins, within -depth_d <= z < 0); none otherwise. depth_top_d 0, depth_bottom_d the deepest
// bin's depth.
std::optional<CreepBand> first_decade_decay(const std::vector<double>& z, const std::vector<double>& u,
                                            double depth_d = CreepSettings{}.depth_d);

// The band as "<top>-<bottom> d".
std::string band_label(const CreepBand& band);

// The measure in one paragraph: lambda over its fit range with the floor and the bands, or the
// verdict.
std::string creep_summary(const CreepMeasure& creep);

// The verdict (when unresolved) and the bands that do not decay: a run's warnings.
std::vector<std::string> creep_problems(const CreepMeasure& creep);

}  // namespace cdpost
