// Fits of profiles against height: the time-averaged velocity u(z) and the oscillation
// amplitude by layer, in reduced units (z in d, velocities in sqrt(g d)).
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

// y = y0 exp(z / lambda) fitted as a line to ln y (every y > 0, at least 3 points). The slope
// 1/lambda is fitted, not lambda: it may be zero or negative.
struct ExponentialFit {
  Estimate inverse_length;  // 1/lambda, 1/d
  Estimate y0;
  FitResult raw;  // of ln y: residuals are logarithmic
};
ExponentialFit fit_exponential(const std::vector<double>& z, const std::vector<double>& y);
// lambda = 1/slope with its propagated error; the slope must be positive.
Estimate decay_length(const Estimate& inverse_length);

// The decay with depth of the oscillation amplitude a(z) at the run's peak frequency, one
// point per layer: a = a_s exp(z / lambda) over the layers lying wholly in the flowing layer
// 0 <= z <= h (the bed below z = 0, where the oscillation dies much faster, is another regime
// and left out). Throws AnalysisError saying why when the fit is not meaningful: fewer than 3
// such layers, a zero amplitude, or a slope that is not positive by at least twice its error.
struct DepthDecay {
  Estimate lambda;  // d
  int layers = 0;
  double log_rms_residual = 0;  // rms of ln a about the fit
};
DepthDecay fit_depth_decay(const std::vector<double>& z, const std::vector<double>& amplitude, double h);

}  // namespace cdpost
