// Fits of the time-averaged velocity profile u(z), in reduced units (z in d, u in sqrt(g d)).
#pragma once

#include <vector>

#include "fit/linear_fit.h"

namespace cdpost {

// Bagnold shape above the bed: u(z) = slip + amplitude * (h^1.5 - (h - z)^1.5) for
// 0 <= z <= h, with h the measured layer thickness (fixed, not fitted).
struct BagnoldFit {
  Estimate slip;       // sqrt(g d)
  Estimate amplitude;  // sqrt(g d) / d^1.5
  double h = 0;        // d
  double r_squared = 0;
  int points = 0;
};
BagnoldFit fit_bagnold(const std::vector<double>& z, const std::vector<double>& u, double h);
double bagnold_velocity(const BagnoldFit& fit, double z);

// Creep in the bed: u(z) = u0 exp(z / lambda) for z < 0, fitted as a line to ln u over the
// points with u > 0 and z_min <= z < 0.
struct CreepFit {
  Estimate lambda;  // d
  Estimate u0;      // sqrt(g d)
  int points = 0;
};
CreepFit fit_creep(const std::vector<double>& z, const std::vector<double>& u, double z_min);

}  // namespace cdpost
