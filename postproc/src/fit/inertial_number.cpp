#include "fit/inertial_number.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "fit/linear_fit.h"

namespace cdpost {

namespace {

constexpr double kBagnoldBaseShear = 2.5;  // du/dz at the base of a Bagnold layer, in U/h
constexpr int kMinBandBins = 3;

double cos_deg(double degrees)
{
  return std::cos(degrees * M_PI / 180);
}

}  // namespace

double bagnold_inertial_number(double velocity, double thickness_d, double phi, double theta_deg)
{
  return kBagnoldBaseShear * velocity / (std::pow(thickness_d, 1.5) * std::sqrt(phi * cos_deg(theta_deg)));
}

LocalInertialNumber local_inertial_number(const std::vector<double>& z_d, const std::vector<double>& u,
                                          const std::vector<double>& phi, double z_at, double half_width_d,
                                          double theta_deg)
{
  if (z_d.size() < 2 || u.size() != z_d.size() || phi.size() != z_d.size())
    throw AnalysisError("the local inertial number needs u and phi in every bin of a profile of 2 bins or more");
  double width = INFINITY;  // the bins' width: their narrowest spacing (empty bins may be left out)
  for (size_t i = 1; i < z_d.size(); ++i) width = std::min(width, z_d[i] - z_d[i - 1]);
  LocalInertialNumber local;
  local.z_d = z_at;
  std::vector<double> band_z, band_u;
  double phi_sum = 0;
  for (size_t i = 0; i < z_d.size(); ++i) {
    const double bottom = z_d[i] - width / 2, top = z_d[i] + width / 2;
    if (top > z_at) local.pressure += phi[i] * (top - std::max(bottom, z_at));
    if (std::abs(z_d[i] - z_at) <= half_width_d) {
      band_z.push_back(z_d[i]);
      band_u.push_back(u[i]);
      phi_sum += phi[i];
    }
  }
  local.pressure *= cos_deg(theta_deg);
  local.bins = static_cast<int>(band_z.size());
  if (local.bins < kMinBandBins)
    throw AnalysisError("the local inertial number needs " + std::to_string(kMinBandBins) + " bins within " +
                        format_estimate(half_width_d, std::nullopt) +
                        " d of z = " + format_estimate(z_at, std::nullopt) + " d");
  if (!(local.pressure > 0)) throw AnalysisError("no grains above the height of the local inertial number");
  Eigen::MatrixXd design(local.bins, 2);
  for (int i = 0; i < local.bins; ++i) design(i, 0) = 1, design(i, 1) = band_z[static_cast<size_t>(i)];
  const auto line = fit_linear(design, band_u, {"u0", "shear_rate"});
  local.shear_rate = line["shear_rate"];
  local.phi = phi_sum / local.bins;
  const double scale = 1 / std::sqrt(local.pressure);
  local.inertial = {local.shear_rate.value * scale, std::nullopt};
  if (local.shear_rate.error) local.inertial.error = *local.shear_rate.error * scale;
  return local;
}

}  // namespace cdpost
