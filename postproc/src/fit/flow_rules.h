// Flow rules across a series of runs (doc/scene.md): Pouliquen's rule, the mu(I) rule, and the
// linear phi(U) law. Angles in degrees, I = d U / (sqrt(g) h^1.5) dimensionless.
//
// Pouliquen's tan θ = tan θ1 + (tan θ2 − tan θ1) exp(−(β h / (ℓ d)) sqrt(g h) / U) depends on
// the run only through (h/d) sqrt(g h)/U = 1/I, so both rules are fitted as tan θ(I); in it β
// and ℓ enter only as β/ℓ. Written as Fr = U/sqrt(g h) = β h/h_stop(θ), the rule's h_stop is
// the thickness at which a layer stops, tan θ = tan θ1 + (tan θ2 − tan θ1) exp(−h_stop/(ℓ d)):
// runs that stopped measure ℓ alone, and with them β is determined.
//
// Every fit keeps its residuals (observed − fitted, in tan θ or phi) per run.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fit/linear_fit.h"

namespace cdpost {

// One run of a series, as the flow rules see it.
struct FlowPoint {
  std::string run;       // names the run in the residuals
  double mu = 0;         // contact friction coefficient (groups the runs)
  double theta_deg = 0;  // tilt
  double inertial_number = 0;
  double velocity = 0;        // U / sqrt(g d)
  std::optional<double> phi;  // area fraction of the flowing layer
};

// A run that stopped at tilt θ, leaving a deposit of thickness h_stop.
struct StopPoint {
  std::string run;
  double mu = 0;
  double theta_deg = 0;
  double h_stop_d = 0;
};

struct PointResidual {
  std::string run;
  double value = 0;  // observed − fitted
};

struct AngleBounds {  // θ1 and θ2 of one friction coefficient
  double mu = 0;
  Estimate theta1_deg;
  Estimate theta2_deg;
};

struct PouliquenFit {
  AngleBounds angles;
  Estimate ell;  // ℓ, dimensionless
  double beta = 0;
  FitResult raw;
  std::vector<PointResidual> residuals;
};
// Fits θ1, θ2, ℓ to the points of one friction coefficient (at least 3 points).
PouliquenFit fit_pouliquen(const std::vector<FlowPoint>& points, double beta);
// The rule refitted with ℓ held at `ell`: θ1, θ2 free (`ell` has no error; raw holds tan θ1, tan θ2).
PouliquenFit fit_pouliquen_held_ell(const std::vector<FlowPoint>& points, double beta, double ell);
double pouliquen_tan(double inertial_number, double tan1, double tan2, double ell, double beta);
// I for which the rule gives tan θ; none outside (tan θ1, tan θ2).
std::optional<double> pouliquen_inertial_number(double tan_theta, const PouliquenFit& fit);

// Pouliquen's rule with β free, for one friction coefficient. With stopped runs, θ1, θ2, ℓ and
// β are fitted jointly to the flowing runs (tan θ against I) and the stopped ones (tan θ
// against h_stop), residuals in tan θ. Without, only ℓ/β is determined (the fit at β = 1),
// and θ1, θ2 are those of the fit at any fixed β.
struct PouliquenFreeFit {
  AngleBounds angles;
  Estimate ell_over_beta;
  std::optional<Estimate> ell, beta;  // only with stopped runs
  int stopped_runs = 0;
  FitResult raw;
  std::vector<PointResidual> residuals;  // the flowing runs, then the stopped ones
};
// At least 3 flowing runs; every point of one friction coefficient.
PouliquenFreeFit fit_pouliquen_free(const std::vector<FlowPoint>& flowing, const std::vector<StopPoint>& stopped);
// tan θ at which a layer of thickness h_stop (in d) stops.
double pouliquen_stop_tan(double h_stop_d, double tan1, double tan2, double ell);
// h_stop(θ) in d; none outside (tan θ1, tan θ2).
std::optional<double> pouliquen_stop_thickness(double tan_theta, double tan1, double tan2, double ell);

struct MuIFit {
  Estimate i0;  // shared by every friction coefficient
  std::vector<AngleBounds> angles;
  FitResult raw;
  std::vector<PointResidual> residuals;
};
// Joint fit over all the points: one I0, θ1 and θ2 per friction coefficient.
MuIFit fit_mu_of_i(const std::vector<FlowPoint>& points);
// The rule refitted with I0 held at `i0`: θ1, θ2 per friction free (`i0` has no error).
MuIFit fit_mu_of_i_held_i0(const std::vector<FlowPoint>& points, double i0);
double mu_of_i_tan(double inertial_number, double tan1, double tan2, double i0);
std::optional<double> mu_of_i_inertial_number(double tan_theta, const AngleBounds& angles, double i0);

struct PhiFit {
  Estimate k;                                      // shared slope, in phi per unit of the abscissa
  std::vector<std::pair<double, Estimate>> phi_c;  // per friction coefficient
  FitResult raw;
  std::vector<PointResidual> residuals;  // in phi, of the points that have phi
};
// phi = phi_c(mu) − k U/sqrt(g d) over the points that have phi.
PhiFit fit_phi_velocity(const std::vector<FlowPoint>& points);
// phi = phi_c(mu) − k_I I over the points that have phi.
PhiFit fit_phi_inertial(const std::vector<FlowPoint>& points);

// The distinct friction coefficients, ascending.
std::vector<double> friction_values(const std::vector<FlowPoint>& points);
std::vector<FlowPoint> points_with_mu(const std::vector<FlowPoint>& points, double mu);
// The distinct angles the points were run at. A rule of tan θ against I is determined only by
// runs at as many angles per friction coefficient as it has parameters there, or more.
size_t angle_count(const std::vector<FlowPoint>& points);
constexpr size_t kPouliquenAngles = 3;  // θ1, θ2, ℓ per friction (β fixed or shared)
constexpr size_t kMuOfIAngles = 2;      // θ1, θ2 per friction, I0 shared

}  // namespace cdpost
