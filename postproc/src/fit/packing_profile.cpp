#include "fit/packing_profile.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "signal/statistics.h"

namespace cdpost {

namespace {

std::string number(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

void require_profile(const PackingProfile& profile, double h_d)
{
  if (profile.z_d.size() != profile.phi.size()) throw AnalysisError("phi(z): as many heights as values needed");
  if (!(h_d > 0)) throw AnalysisError("phi(z): the layer thickness must be positive, got " + number(h_d));
  for (size_t i = 1; i < profile.z_d.size(); ++i)
    if (!(profile.z_d[i] > profile.z_d[i - 1])) throw AnalysisError("phi(z): bin heights must ascend");
}

}  // namespace

double bulk_packing(const PackingProfile& profile, double h_d)
{
  require_profile(profile, h_d);
  double sum = 0;
  int bins = 0;
  for (size_t i = 0; i < profile.z_d.size(); ++i)
    if (profile.z_d[i] >= kBulkBottom * h_d && profile.z_d[i] <= kBulkTop * h_d) sum += profile.phi[i], ++bins;
  if (bins < 3)
    throw AnalysisError("phi(z) has " + std::to_string(bins) + " bins between 0.2 h and 0.8 h (h = " + number(h_d) +
                        " d); the bulk packing needs 3");
  return sum / bins;
}

double half_packing_height(const PackingProfile& profile, double bulk, double h_d)
{
  require_profile(profile, h_d);
  const double half = 0.5 * bulk;
  for (size_t i = 1; i < profile.z_d.size(); ++i) {
    if (profile.z_d[i] <= kBulkTop * h_d || profile.phi[i] >= half) continue;
    const double above = profile.phi[i], below = profile.phi[i - 1];
    if (below < half) break;  // the bin below the window's top is already dilute: no bulk to fall from
    return profile.z_d[i - 1] + (below - half) / (below - above) * (profile.z_d[i] - profile.z_d[i - 1]);
  }
  throw AnalysisError("phi(z) does not fall from the bulk to half its bulk value (" + number(half) +
                      ") above 0.8 h (h = " + number(h_d) + " d) inside the profile");
}

double mean_grain_area_d2(double dispersity)
{
  return M_PI / 4 * (1 + dispersity * dispersity / 12);
}

std::vector<double> packing_from_counts(const std::vector<double>& counts, double length_d, double bin_width_d,
                                        double dispersity)
{
  if (!(length_d > 0 && bin_width_d > 0))
    throw AnalysisError("phi from counts needs a positive cell length and bin width, got L = " + number(length_d) +
                        " d, bin " + number(bin_width_d) + " d");
  if (!(dispersity >= 0 && dispersity < 1))
    throw AnalysisError("phi from counts: the dispersity must be in [0, 1), got " + number(dispersity));
  std::vector<double> phi;
  const double area = mean_grain_area_d2(dispersity);
  for (double count : counts) phi.push_back(count * area / (length_d * bin_width_d));
  return phi;
}

}  // namespace cdpost
