// Siconos's solvers at options other than their defaults, by name (doc/peers.md):
// "SOLVER[KEY=VALUE+KEY=VALUE]", e.g. "fc3d_nsn_fb[ls=armijo]", "fc3d_nsgs[local=pli+shuffle=each]".
// Each key sets the iparam/dparam entry, or the internal solver, that Siconos numerics 4.4's headers
// document (Friction_cst.h, fc3d_Solvers.h); the studied set follows the variants of Acary, Brémond
// & Huber (2018). Keys per solver:
//   fc3d_nsn_ac, fc3d_nsn_fb, fc3d_nsn_nm: ls (gp, armijo, none), hybrid (no, pli_nsn, nsn_pli, vi_eg_nsn);
//     fc3d_nsn_ac also form (ac, jm, ac_gen, jm_gen), rho (constant, spectral, split_cond, split, adaptive)
//   fc3d_nsgs: local (nsn, nsn_gp, nsn_gp_hybrid, pli, p, quartic), local_form (ac, jm),
//     local_hybrid (no, pli_nsn, nsn_pli), local_tol (its strategy: adaptive, given, adaptive_n),
//     local_tolerance (its value), shuffle (no, once, each), omega (a relaxation factor),
//     error (full, light, light_full_final, adaptive)
//   fc3d_admm: rho (constant, residual_balancing, scaled_residual_balancing),
//     initial_rho (given, norm_inf, eigenvalues), accel (no, yes, restart)
//   fc3d_prox: inner (nsn_ac, nsn_fb, nsgs), strategy (prox, regularization), alpha, sigma, nu
//   fc3d_tfp: inner (nsgs, pg_cylinder, vi_fpp_cylinder)
// Values are names or numbers (write 1e4, not 1e+4: '+' separates options).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

struct SolverOptions;  // Siconos numerics' (SolverOptions.h)

namespace peers {

struct VariantName {
  std::string solver;                                        // the solver, e.g. "fc3d_nsn_fb"
  std::vector<std::pair<std::string, std::string>> options;  // its keys and values, in order
};

// Splits "SOLVER[K=V+K=V]" (a bare SOLVER: no options). Throws std::invalid_argument if malformed.
VariantName parse_variant(const std::string& name);

// Applies the variant's options to `options` (Siconos's defaults for its solver). Throws
// std::invalid_argument, in one line naming the variant, for a key or value it does not know.
void apply_variant(const VariantName& variant, SolverOptions& options);

// The variants this comparison studies (doc/peers.md), screened beside the defaults.
const std::vector<std::string>& siconos_variant_names();

}  // namespace peers
