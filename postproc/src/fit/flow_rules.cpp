#include "fit/flow_rules.h"

#include <algorithm>
#include <cmath>

#include "fit/nonlinear_fit.h"

namespace cdpost {

namespace {

constexpr double degrees_per_radian = 180.0 / M_PI;
double tan_deg(double degrees) { return std::tan(degrees / degrees_per_radian); }

// θ = atan(t) with dθ = dt / (1 + t²), in degrees.
Estimate angle_of_tangent(const Estimate& tangent) {
  Estimate angle{std::atan(tangent.value) * degrees_per_radian, std::nullopt};
  if (tangent.error) angle.error = *tangent.error / (1 + tangent.value * tangent.value) * degrees_per_radian;
  return angle;
}

std::vector<double> tangents(const std::vector<FlowPoint>& points) {
  std::vector<double> t;
  for (const auto& p : points) t.push_back(tan_deg(p.theta_deg));
  return t;
}

// Starting bounds just outside the observed range of tan θ.
std::pair<double, double> initial_tangents(const std::vector<double>& t) {
  auto [low, high] = std::minmax_element(t.begin(), t.end());
  double margin = 0.1 * std::max(*high - *low, 0.02);
  return {*low - margin, *high + margin};
}

// The run of median angle: where the initial guesses of ℓ and I0 are taken.
FlowPoint median_point(std::vector<FlowPoint> points) {
  std::nth_element(points.begin(), points.begin() + points.size() / 2, points.end(),
                   [](const FlowPoint& a, const FlowPoint& b) { return a.theta_deg < b.theta_deg; });
  return points[points.size() / 2];
}

}  // namespace

std::vector<double> friction_values(const std::vector<FlowPoint>& points) {
  std::vector<double> mus;
  for (const auto& p : points)
    if (std::find(mus.begin(), mus.end(), p.mu) == mus.end()) mus.push_back(p.mu);
  std::sort(mus.begin(), mus.end());
  return mus;
}

std::vector<FlowPoint> points_with_mu(const std::vector<FlowPoint>& points, double mu) {
  std::vector<FlowPoint> selected;
  std::copy_if(points.begin(), points.end(), std::back_inserter(selected), [mu](const FlowPoint& p) { return p.mu == mu; });
  return selected;
}

double pouliquen_tan(double inertial_number, double tan1, double tan2, double ell, double beta) {
  return tan1 + (tan2 - tan1) * std::exp(-beta / (ell * inertial_number));
}

PouliquenFit fit_pouliquen(const std::vector<FlowPoint>& points, double beta) {
  if (points.size() < 3) throw AnalysisError("Pouliquen's rule needs at least 3 runs per friction coefficient");
  const auto observed = tangents(points);
  auto [tan1, tan2] = initial_tangents(observed);
  const auto middle = median_point(points);
  double ell = -beta / (middle.inertial_number * std::log((tan_deg(middle.theta_deg) - tan1) / (tan2 - tan1)));
  auto model = [&](const std::vector<double>& p, size_t i) {
    return pouliquen_tan(points[i].inertial_number, p[0], p[1], p[2], beta);
  };
  PouliquenFit fit;
  fit.raw = fit_nonlinear(observed, model, {tan1, tan2, ell}, {"tan_theta1", "tan_theta2", "ell"});
  fit.angles = {points.front().mu, angle_of_tangent(fit.raw["tan_theta1"]), angle_of_tangent(fit.raw["tan_theta2"])};
  fit.ell = fit.raw["ell"];
  fit.beta = beta;
  return fit;
}

std::optional<double> pouliquen_inertial_number(double tan_theta, const PouliquenFit& fit) {
  double tan1 = fit.raw["tan_theta1"].value, tan2 = fit.raw["tan_theta2"].value;
  double fraction = (tan_theta - tan1) / (tan2 - tan1);
  if (!(fraction > 0 && fraction < 1)) return std::nullopt;
  return -fit.beta / (fit.ell.value * std::log(fraction));
}

double mu_of_i_tan(double inertial_number, double tan1, double tan2, double i0) {
  return tan1 + (tan2 - tan1) / (i0 / inertial_number + 1);
}

std::optional<double> mu_of_i_inertial_number(double tan_theta, const AngleBounds& angles, double i0) {
  double tan1 = tan_deg(angles.theta1_deg.value), tan2 = tan_deg(angles.theta2_deg.value);
  if (!(tan_theta > tan1 && tan_theta < tan2)) return std::nullopt;
  return i0 * (tan_theta - tan1) / (tan2 - tan_theta);
}

MuIFit fit_mu_of_i(const std::vector<FlowPoint>& points) {
  const auto mus = friction_values(points);
  const auto observed = tangents(points);
  std::vector<size_t> group;  // friction coefficient index of each point
  for (const auto& p : points) group.push_back(static_cast<size_t>(std::find(mus.begin(), mus.end(), p.mu) - mus.begin()));
  std::vector<double> initial{median_point(points).inertial_number};
  std::vector<std::string> names{"I0"};
  for (size_t m = 0; m < mus.size(); ++m) {
    auto [tan1, tan2] = initial_tangents(tangents(points_with_mu(points, mus[m])));
    initial.insert(initial.end(), {tan1, tan2});
    names.insert(names.end(), {"tan_theta1_" + std::to_string(m), "tan_theta2_" + std::to_string(m)});
  }
  auto model = [&](const std::vector<double>& p, size_t i) {
    return mu_of_i_tan(points[i].inertial_number, p[1 + 2 * group[i]], p[2 + 2 * group[i]], p[0]);
  };
  MuIFit fit;
  fit.raw = fit_nonlinear(observed, model, initial, names);
  fit.i0 = fit.raw.parameters[0];
  for (size_t m = 0; m < mus.size(); ++m)
    fit.angles.push_back({mus[m], angle_of_tangent(fit.raw.parameters[1 + 2 * m]), angle_of_tangent(fit.raw.parameters[2 + 2 * m])});
  return fit;
}

PhiFit fit_phi_velocity(const std::vector<FlowPoint>& points) {
  std::vector<FlowPoint> with_phi;
  std::copy_if(points.begin(), points.end(), std::back_inserter(with_phi), [](const FlowPoint& p) { return p.phi.has_value(); });
  const auto mus = friction_values(with_phi);
  Eigen::MatrixXd design = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(with_phi.size()), static_cast<Eigen::Index>(mus.size() + 1));
  std::vector<double> phi;
  for (size_t i = 0; i < with_phi.size(); ++i) {
    auto m = std::find(mus.begin(), mus.end(), with_phi[i].mu) - mus.begin();
    design(static_cast<Eigen::Index>(i), m) = 1.0;
    design(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(mus.size())) = -with_phi[i].velocity;
    phi.push_back(*with_phi[i].phi);
  }
  std::vector<std::string> names;
  for (size_t m = 0; m < mus.size(); ++m) names.push_back("phi_c_" + std::to_string(m));
  names.push_back("k");
  PhiFit fit;
  fit.raw = fit_linear(design, phi, names);
  fit.k = fit.raw["k"];
  for (size_t m = 0; m < mus.size(); ++m) fit.phi_c.emplace_back(mus[m], fit.raw.parameters[m]);
  return fit;
}

}  // namespace cdpost
