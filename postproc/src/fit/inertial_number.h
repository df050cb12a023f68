// The inertial number of a chute run read three ways (doc/source.md, "The source's two flow
// rules"), all in reduced units (lengths in d, velocities in sqrt(g d), rho the grains' density):
//
// - the source's stated I = d U / (sqrt(g) h^1.5), the result I of a run;
// - GDR MiDi's I = gamma_dot d / sqrt(P / rho) with the Bagnold shear rate and the basal pressure:
//   for u(z) = a (h^1.5 - (h - z)^1.5) the mean velocity is U = 3/5 a h^1.5 and du/dz at the base
//   1.5 a h^0.5 = 5 U / (2 h); the weight above the base is P = phi rho g h cos theta. Then
//   I = 2.5 U / (h^1.5 sqrt(phi cos theta)), the stated I times 2.5 / sqrt(phi cos theta); in a
//   Bagnold layer gamma_dot grows as (h - z)^0.5 and P as (h - z), so this I holds at every depth;
// - the local I at a height z from the measured profiles: du/dz of u(z), and P(z) the weight of
//   the grains above z, rho g cos theta times the integral of phi(z') from z up (the momentum
//   balance of a steady flow uniform along x: d sigma_zz / dz = -phi rho g cos theta).
#pragma once

#include <vector>

#include "signal/statistics.h"

namespace cdpost {

// GDR MiDi's I of a Bagnold layer of mean velocity U (sqrt(g d)), thickness h (d) and packing phi at tilt theta.
double bagnold_inertial_number(double velocity, double thickness_d, double phi, double theta_deg);

// Where the local I is read: the middle of the layer, the shear rate fitted over a band of this
// half-width (a fraction of h) around it.
constexpr double kLocalHeightFraction = 0.5;
constexpr double kLocalBandFraction = 0.1;

struct LocalInertialNumber {
  double z_d = 0;       // the height read, above the wall tops
  Estimate shear_rate;  // du/dz, sqrt(g/d): the slope of a line fitted to u over the band
  double pressure = 0;  // P / (rho g d): cos theta times the integral of phi from z_d up
  double phi = 0;       // mean phi of the band's bins
  Estimate inertial;    // shear_rate / sqrt(pressure), the error from the slope's
  int bins = 0;         // in the band
};

// Bins of equal width (their narrowest spacing: empty bins may be left out), centres z_d
// ascending, u and phi per bin. The shear rate is fitted over the
// bins centred within z_at +- half_width_d (at least 3); the bin holding z_at counts in the
// pressure for its part above z_at. Throws AnalysisError when the band has fewer than 3 bins or
// the grains above z_at weigh nothing.
LocalInertialNumber local_inertial_number(const std::vector<double>& z_d, const std::vector<double>& u,
                                          const std::vector<double>& phi, double z_at, double half_width_d,
                                          double theta_deg);

}  // namespace cdpost
