#include "fit/flow_rules.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "fit/nonlinear_fit.h"

namespace cdpost {

namespace {

constexpr double degrees_per_radian = 180.0 / M_PI;
double tan_deg(double degrees)
{
  return std::tan(degrees / degrees_per_radian);
}

// θ = atan(t) with dθ = dt / (1 + t²), in degrees.
Estimate angle_of_tangent(const Estimate& tangent)
{
  Estimate angle{std::atan(tangent.value) * degrees_per_radian, std::nullopt};
  if (tangent.error) angle.error = *tangent.error / (1 + tangent.value * tangent.value) * degrees_per_radian;
  return angle;
}

template <class Point>
std::vector<double> tangents(const std::vector<Point>& points)
{
  std::vector<double> t;
  for (const auto& p : points) t.push_back(tan_deg(p.theta_deg));
  return t;
}

template <class Point>
std::vector<std::string> run_names(const std::vector<Point>& points)
{
  std::vector<std::string> names;
  for (const auto& p : points) names.push_back(p.run);
  return names;
}

// The residuals of `fit`, whose points are those of the runs named, in order.
std::vector<PointResidual> named_residuals(const std::vector<std::string>& runs, const FitResult& fit)
{
  std::vector<PointResidual> residuals;
  for (size_t i = 0; i < runs.size(); ++i) residuals.push_back({runs[i], fit.residuals[i]});
  return residuals;
}

// p[a]/p[b] with its error from the covariance (first order).
Estimate parameter_ratio(const FitResult& fit, Eigen::Index a, Eigen::Index b)
{
  const double pa = fit.parameters[a].value, pb = fit.parameters[b].value;
  Estimate ratio{pa / pb, std::nullopt};
  if (fit.covariance.size() == 0) return ratio;
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(fit.covariance.rows());
  gradient(a) = 1 / pb;
  gradient(b) = -pa / (pb * pb);
  const double variance = gradient.dot(fit.covariance * gradient);
  if (std::isfinite(variance) && variance >= 0) ratio.error = std::sqrt(variance);
  return ratio;
}

// Starting bounds just outside the observed range of tan θ.
std::pair<double, double> initial_tangents(const std::vector<double>& t)
{
  auto [low, high] = std::minmax_element(t.begin(), t.end());
  double margin = 0.1 * std::max(*high - *low, 0.02);
  return {*low - margin, *high + margin};
}

// The run of median angle: where the initial guesses of ℓ and I0 are taken.
FlowPoint median_point(std::vector<FlowPoint> points)
{
  std::nth_element(points.begin(), points.begin() + points.size() / 2, points.end(),
                   [](const FlowPoint& a, const FlowPoint& b) { return a.theta_deg < b.theta_deg; });
  return points[points.size() / 2];
}

}  // namespace

std::vector<double> friction_values(const std::vector<FlowPoint>& points)
{
  std::vector<double> mus;
  for (const auto& p : points)
    if (std::find(mus.begin(), mus.end(), p.mu) == mus.end()) mus.push_back(p.mu);
  std::sort(mus.begin(), mus.end());
  return mus;
}

std::vector<FlowPoint> points_with_mu(const std::vector<FlowPoint>& points, double mu)
{
  std::vector<FlowPoint> selected;
  std::copy_if(points.begin(), points.end(), std::back_inserter(selected),
               [mu](const FlowPoint& p) { return p.mu == mu; });
  return selected;
}

size_t angle_count(const std::vector<FlowPoint>& points)
{
  std::set<double> angles;
  for (const auto& p : points) angles.insert(p.theta_deg);
  return angles.size();
}

namespace {

// Throws unless `points` (of one friction coefficient) span `needed` angles.
void require_angles(const std::vector<FlowPoint>& points, size_t needed, const std::string& rule)
{
  if (size_t found = angle_count(points); found < needed) {
    std::ostringstream text;
    text << rule << " needs runs at " << needed << " or more angles per friction coefficient";
    if (!points.empty()) text << "; mu = " << points.front().mu << " has " << found;
    throw AnalysisError(text.str());
  }
}

}  // namespace

double pouliquen_tan(double inertial_number, double tan1, double tan2, double ell, double beta)
{
  return tan1 + (tan2 - tan1) * std::exp(-beta / (ell * inertial_number));
}

namespace {

// θ1, θ2 and, unless `held_ell` gives it, ℓ.
PouliquenFit fit_pouliquen_with(const std::vector<FlowPoint>& points, double beta, std::optional<double> held_ell)
{
  require_angles(points, held_ell ? 2 : kPouliquenAngles, "Pouliquen's rule");
  const auto observed = tangents(points);
  auto [tan1, tan2] = initial_tangents(observed);
  const auto middle = median_point(points);
  double ell = -beta / (middle.inertial_number * std::log((tan_deg(middle.theta_deg) - tan1) / (tan2 - tan1)));
  auto model = [&](const std::vector<double>& p, size_t i) {
    return pouliquen_tan(points[i].inertial_number, p[0], p[1], held_ell ? *held_ell : p[2], beta);
  };
  PouliquenFit fit;
  if (held_ell) fit.raw = fit_nonlinear(observed, model, {tan1, tan2}, {"tan_theta1", "tan_theta2"});
  else fit.raw = fit_nonlinear(observed, model, {tan1, tan2, ell}, {"tan_theta1", "tan_theta2", "ell"});
  fit.angles = {points.front().mu, angle_of_tangent(fit.raw["tan_theta1"]), angle_of_tangent(fit.raw["tan_theta2"])};
  fit.ell = held_ell ? Estimate{*held_ell, std::nullopt} : fit.raw["ell"];
  fit.beta = beta;
  fit.residuals = named_residuals(run_names(points), fit.raw);
  return fit;
}

}  // namespace

PouliquenFit fit_pouliquen(const std::vector<FlowPoint>& points, double beta)
{
  return fit_pouliquen_with(points, beta, std::nullopt);
}

PouliquenFit fit_pouliquen_held_ell(const std::vector<FlowPoint>& points, double beta, double ell)
{
  if (!(ell > 0)) throw AnalysisError("Pouliquen's rule: a held l must be positive");
  return fit_pouliquen_with(points, beta, ell);
}

double pouliquen_stop_tan(double h_stop_d, double tan1, double tan2, double ell)
{
  return tan1 + (tan2 - tan1) * std::exp(-h_stop_d / ell);
}

std::optional<double> pouliquen_stop_thickness(double tan_theta, double tan1, double tan2, double ell)
{
  double fraction = (tan_theta - tan1) / (tan2 - tan1);
  if (!(fraction > 0 && fraction < 1)) return std::nullopt;
  return -ell * std::log(fraction);
}

// Fr = β h/h_stop is I = β/(h_stop/d).
std::optional<double> pouliquen_inertial_number(double tan_theta, const PouliquenFit& fit)
{
  auto h_stop =
      pouliquen_stop_thickness(tan_theta, fit.raw["tan_theta1"].value, fit.raw["tan_theta2"].value, fit.ell.value);
  if (!h_stop) return std::nullopt;
  return fit.beta / *h_stop;
}

namespace {

// Start of the joint fit: the bounds widened to hold every run, ℓ from the stopped runs at
// those bounds (median), β from the flowing runs' ℓ/β.
std::vector<double> joint_start(const std::vector<FlowPoint>& flowing, const std::vector<StopPoint>& stopped,
                                const PouliquenFit& ratio)
{
  auto all = tangents(flowing);
  for (double t : tangents(stopped)) all.push_back(t);
  const auto around_all = initial_tangents(all);
  const double tan1 = std::min(ratio.raw["tan_theta1"].value, around_all.first);
  const double tan2 = std::max(ratio.raw["tan_theta2"].value, around_all.second);
  std::vector<double> lengths;
  for (const auto& s : stopped)
    if (double fraction = (tan_deg(s.theta_deg) - tan1) / (tan2 - tan1); fraction > 0 && fraction < 1)
      lengths.push_back(-s.h_stop_d / std::log(fraction));
  double ell = stopped.front().h_stop_d;  // when no stopped run lies between the bounds
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    ell = lengths[lengths.size() / 2];
  }
  return {tan1, tan2, ell, ell / ratio.ell.value};
}

}  // namespace

PouliquenFreeFit fit_pouliquen_free(const std::vector<FlowPoint>& flowing, const std::vector<StopPoint>& stopped)
{
  const auto ratio = fit_pouliquen(flowing, 1.0);  // ℓ at β = 1 is ℓ/β
  PouliquenFreeFit fit;
  fit.stopped_runs = static_cast<int>(stopped.size());
  if (stopped.empty()) {
    fit.angles = ratio.angles;
    fit.ell_over_beta = ratio.ell;
    fit.raw = ratio.raw;
    fit.residuals = ratio.residuals;
    return fit;
  }
  auto observed = tangents(flowing);
  for (double t : tangents(stopped)) observed.push_back(t);
  const size_t n_flowing = flowing.size();
  auto model = [&](const std::vector<double>& p, size_t i) {
    return i < n_flowing ? pouliquen_tan(flowing[i].inertial_number, p[0], p[1], p[2], p[3])
                         : pouliquen_stop_tan(stopped[i - n_flowing].h_stop_d, p[0], p[1], p[2]);
  };
  fit.raw =
      fit_nonlinear(observed, model, joint_start(flowing, stopped, ratio), {"tan_theta1", "tan_theta2", "ell", "beta"});
  fit.ell = fit.raw["ell"];
  fit.beta = fit.raw["beta"];
  if (!(fit.ell->value > 0 && fit.beta->value > 0))
    throw AnalysisError("the joint fit gives a length l or a beta that is not positive");
  fit.angles = {flowing.front().mu, angle_of_tangent(fit.raw["tan_theta1"]), angle_of_tangent(fit.raw["tan_theta2"])};
  fit.ell_over_beta = parameter_ratio(fit.raw, 2, 3);
  auto runs = run_names(flowing);
  for (const auto& name : run_names(stopped)) runs.push_back(name);
  fit.residuals = named_residuals(runs, fit.raw);
  return fit;
}

double mu_of_i_tan(double inertial_number, double tan1, double tan2, double i0)
{
  return tan1 + (tan2 - tan1) / (i0 / inertial_number + 1);
}

std::optional<double> mu_of_i_inertial_number(double tan_theta, const AngleBounds& angles, double i0)
{
  double tan1 = tan_deg(angles.theta1_deg.value), tan2 = tan_deg(angles.theta2_deg.value);
  if (!(tan_theta > tan1 && tan_theta < tan2)) return std::nullopt;
  return i0 * (tan_theta - tan1) / (tan2 - tan_theta);
}

namespace {

// θ1, θ2 per friction and, unless `held_i0` gives it, I0 (then the first parameter).
MuIFit fit_mu_of_i_with(const std::vector<FlowPoint>& points, std::optional<double> held_i0)
{
  const auto mus = friction_values(points);
  if (mus.empty()) throw AnalysisError("the mu(I) rule needs flowing runs");
  for (double mu : mus) require_angles(points_with_mu(points, mu), kMuOfIAngles, "the mu(I) rule");
  const auto observed = tangents(points);
  std::vector<size_t> group;  // friction coefficient index of each point
  for (const auto& p : points)
    group.push_back(static_cast<size_t>(std::find(mus.begin(), mus.end(), p.mu) - mus.begin()));
  const size_t first = held_i0 ? 0 : 1;  // index of tan θ1 of the first friction
  std::vector<double> initial;
  std::vector<std::string> names;
  if (!held_i0) initial.push_back(median_point(points).inertial_number), names.push_back("I0");
  for (size_t m = 0; m < mus.size(); ++m) {
    auto [tan1, tan2] = initial_tangents(tangents(points_with_mu(points, mus[m])));
    initial.insert(initial.end(), {tan1, tan2});
    names.insert(names.end(), {"tan_theta1_" + std::to_string(m), "tan_theta2_" + std::to_string(m)});
  }
  auto model = [&](const std::vector<double>& p, size_t i) {
    return mu_of_i_tan(points[i].inertial_number, p[first + 2 * group[i]], p[first + 1 + 2 * group[i]],
                       held_i0 ? *held_i0 : p[0]);
  };
  MuIFit fit;
  fit.raw = fit_nonlinear(observed, model, initial, names);
  fit.i0 = held_i0 ? Estimate{*held_i0, std::nullopt} : fit.raw.parameters[0];
  fit.residuals = named_residuals(run_names(points), fit.raw);
  for (size_t m = 0; m < mus.size(); ++m)
    fit.angles.push_back({mus[m], angle_of_tangent(fit.raw.parameters[first + 2 * m]),
                          angle_of_tangent(fit.raw.parameters[first + 1 + 2 * m])});
  return fit;
}

}  // namespace

MuIFit fit_mu_of_i(const std::vector<FlowPoint>& points)
{
  return fit_mu_of_i_with(points, std::nullopt);
}

MuIFit fit_mu_of_i_held_i0(const std::vector<FlowPoint>& points, double i0)
{
  if (!(i0 > 0)) throw AnalysisError("the mu(I) rule: a held I0 must be positive");
  return fit_mu_of_i_with(points, i0);
}

namespace {

// phi = phi_c(mu) − k x(point), by linear least squares over the points that have phi.
PhiFit fit_phi_linear(const std::vector<FlowPoint>& points, double (*abscissa)(const FlowPoint&))
{
  std::vector<FlowPoint> with_phi;
  std::copy_if(points.begin(), points.end(), std::back_inserter(with_phi),
               [](const FlowPoint& p) { return p.phi.has_value(); });
  const auto mus = friction_values(with_phi);
  Eigen::MatrixXd design =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(with_phi.size()), static_cast<Eigen::Index>(mus.size() + 1));
  std::vector<double> phi;
  for (size_t i = 0; i < with_phi.size(); ++i) {
    auto m = std::find(mus.begin(), mus.end(), with_phi[i].mu) - mus.begin();
    design(static_cast<Eigen::Index>(i), m) = 1.0;
    design(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(mus.size())) = -abscissa(with_phi[i]);
    phi.push_back(*with_phi[i].phi);
  }
  std::vector<std::string> names;
  for (size_t m = 0; m < mus.size(); ++m) names.push_back("phi_c_" + std::to_string(m));
  names.push_back("k");
  PhiFit fit;
  fit.raw = fit_linear(design, phi, names);
  fit.k = fit.raw["k"];
  for (size_t m = 0; m < mus.size(); ++m) fit.phi_c.emplace_back(mus[m], fit.raw.parameters[m]);
  fit.residuals = named_residuals(run_names(with_phi), fit.raw);
  return fit;
}

}  // namespace

PhiFit fit_phi_velocity(const std::vector<FlowPoint>& points)
{
  return fit_phi_linear(points, [](const FlowPoint& p) { return p.velocity; });
}

PhiFit fit_phi_inertial(const std::vector<FlowPoint>& points)
{
  return fit_phi_linear(points, [](const FlowPoint& p) { return p.inertial_number; });
}

}  // namespace cdpost
