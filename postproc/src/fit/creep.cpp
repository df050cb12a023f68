#include "fit/creep.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "fit/profile_fits.h"

namespace cdpost {

namespace {

std::string text(double value)
{
  return format_estimate(value, std::nullopt);
}

// The bins with -depth <= z < 0, highest first.
struct BedBins {
  std::vector<double> z, u;
};

BedBins bed_bins(const std::vector<double>& z, const std::vector<double>& u, double depth)
{
  std::vector<size_t> order;
  for (size_t i = 0; i < z.size(); ++i)
    if (z[i] < 0 && z[i] >= -depth) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return z[a] > z[b]; });
  BedBins bed;
  for (size_t i : order) {
    bed.z.push_back(z[i]);
    bed.u.push_back(u[i]);
  }
  return bed;
}

// The first bin, from the top, where u is not positive or not smaller than the bin above.
size_t end_of_decay(const BedBins& bed)
{
  for (size_t i = 0; i < bed.u.size(); ++i)
    if (!(bed.u[i] > 0) || (i > 0 && bed.u[i] >= bed.u[i - 1])) return i;
  return bed.u.size();
}

std::optional<CreepFloor> estimated_floor(const BedBins& bed)
{
  const size_t end = end_of_decay(bed);
  const int bins = static_cast<int>(bed.u.size() - end);
  if (bins < kMinFloorBins) return std::nullopt;
  const double squares = std::accumulate(bed.u.begin() + end, bed.u.end(), 0.0,
                                         [](double sum, double value) { return sum + value * value; });
  return CreepFloor{std::sqrt(squares / bins), bins, bed.z[end]};
}

// The local decay lengths over the first `points` bins of the bed, band by band.
void fit_bands(const BedBins& bed, int points, CreepMeasure& creep)
{
  const double deepest = -bed.z[points - 1];
  for (double top = 0; top <= deepest; top += kBandWidthD) {
    CreepBand band{top, top + kBandWidthD, {}, 0};
    std::vector<double> z, u;
    for (int i = 0; i < points; ++i)
      if (-bed.z[i] >= band.depth_top_d && -bed.z[i] < band.depth_bottom_d) {
        z.push_back(bed.z[i]);
        u.push_back(bed.u[i]);
      }
    if (static_cast<int>(z.size()) < kMinBandPoints) continue;
    const auto fit = fit_exponential(z, u);
    if (!(fit.inverse_length.value > 0)) {
      creep.band_problems.push_back("u does not decay over " + band_label(band) + " below the wall tops");
      continue;
    }
    band.lambda = decay_length(fit.inverse_length);
    band.points = fit.raw.points;
    creep.bands.push_back(band);
  }
}

void fit_range(const BedBins& bed, CreepMeasure& creep)
{
  const double threshold = kFloorMultiple * creep.floor->value;
  int points = 0;
  while (points < static_cast<int>(bed.u.size()) && bed.u[points] > threshold) ++points;
  creep.points = points;
  if (points > 0) creep.z_high = bed.z.front(), creep.z_low = bed.z[points - 1];
  if (points < kMinResolvedPoints) {
    creep.verdict = "unresolved: " + std::to_string(points) + " bins below the wall tops before u first falls below " +
                    text(kFloorMultiple) + " x the floor (" + text(creep.floor->value) + " sqrt(g d), " +
                    creep.floor->source() + "); " + std::to_string(kMinResolvedPoints) + " needed";
    return;
  }
  const std::vector<double> z(bed.z.begin(), bed.z.begin() + points), u(bed.u.begin(), bed.u.begin() + points);
  const auto fit = fit_exponential(z, u);
  if (!(fit.inverse_length.value > 0)) {
    creep.verdict = "unresolved: u does not decay over the fit range " + text(creep.z_low) +
                    " <= z <= " + text(creep.z_high) + " d";
    return;
  }
  creep.lambda = decay_length(fit.inverse_length);
  creep.u0 = fit.y0;
  fit_bands(bed, points, creep);
}

}  // namespace

std::string band_label(const CreepBand& band)
{
  return text(band.depth_top_d) + "-" + text(band.depth_bottom_d) + " d";
}

std::optional<CreepBand> first_decade_decay(const std::vector<double>& z, const std::vector<double>& u, double depth_d)
{
  const auto bed = bed_bins(z, u, depth_d);
  const size_t decaying = end_of_decay(bed);
  if (decaying == 0) return std::nullopt;
  const double decade_end = bed.u.front() / 10;
  size_t points = 0;
  while (points < decaying && bed.u[points] >= decade_end) ++points;
  if (static_cast<int>(points) < kMinBandPoints) return std::nullopt;
  const std::vector<double> band_z(bed.z.begin(), bed.z.begin() + static_cast<long>(points)),
      band_u(bed.u.begin(), bed.u.begin() + static_cast<long>(points));
  const auto fit = fit_exponential(band_z, band_u);
  if (!(fit.inverse_length.value > 0)) return std::nullopt;
  return CreepBand{0, -band_z.back(), decay_length(fit.inverse_length), fit.raw.points};
}

std::string CreepFloor::source() const
{
  if (bins == 0) return "given (--creep-floor)";
  return "estimated: rms of u over the " + std::to_string(bins) + " bins from z = " + text(z_top) +
         " d down, where u stops decaying";
}

CreepMeasure measure_creep(const std::vector<double>& z, const std::vector<double>& u, const CreepSettings& settings)
{
  if (!(settings.depth_d > 0)) throw AnalysisError("the creep depth must be positive");
  if (settings.floor_reduced && !(*settings.floor_reduced > 0 && std::isfinite(*settings.floor_reduced)))
    throw AnalysisError("the creep floor must be a positive number");
  if (z.size() != u.size()) throw AnalysisError("the creep measure needs one u per z");
  CreepMeasure creep;
  const auto bed = bed_bins(z, u, settings.depth_d);
  if (bed.z.empty()) {
    creep.verdict = "unresolved: no profile bin with -" + text(settings.depth_d) + " d <= z < 0";
    return creep;
  }
  creep.floor = settings.floor_reduced ? CreepFloor{*settings.floor_reduced, 0, 0} : estimated_floor(bed);
  if (!creep.floor) {
    creep.verdict = "unresolved: u decays without reaching a floor down to z = " + text(bed.z.back()) +
                    " d (fewer than " + std::to_string(kMinFloorBins) +
                    " bins below the decay to estimate it from): give --creep-floor";
    return creep;
  }
  fit_range(bed, creep);
  return creep;
}

std::string creep_summary(const CreepMeasure& creep)
{
  if (!creep.lambda) return "Creep " + creep.verdict + ".";
  std::string summary = "Creep length lambda = " + format_estimate(creep.lambda->value, creep.lambda->error) +
                        " d, fitted over " + text(creep.z_low) + " <= z <= " + text(creep.z_high) + " d (" +
                        std::to_string(creep.points) + " bins, u above " + text(kFloorMultiple) + " x the floor " +
                        text(creep.floor->value) + " sqrt(g d), " + creep.floor->source() + ").";
  if (creep.bands.empty()) return summary;
  summary += " Local decay length by depth below the wall tops:";
  for (size_t i = 0; i < creep.bands.size(); ++i)
    summary += std::string(i ? ";" : "") + " " + band_label(creep.bands[i]) + ": " +
               format_estimate(creep.bands[i].lambda.value, creep.bands[i].lambda.error) + " d";
  return summary + ".";
}

std::vector<std::string> creep_problems(const CreepMeasure& creep)
{
  std::vector<std::string> problems;
  if (!creep.verdict.empty()) problems.push_back(creep.verdict);
  problems.insert(problems.end(), creep.band_problems.begin(), creep.band_problems.end());
  return problems;
}

}  // namespace cdpost
