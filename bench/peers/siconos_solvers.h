// Siconos numerics' frictional-contact solvers on a local problem (bench/peers/local_problem.h):
// one call, one solver by name, from a given start, returning the answer, the work, the error
// and the time. The 2D family (fc2d_*) gets the problem as it is; the 3D family (fc3d_*) gets it
// embedded in 3D with a zero second tangent: q and r zero there, W's second-tangent rows and
// columns zero but for a diagonal equal to the contact's W_tt (a zero diagonal stops every local
// solver), so r_t2 = 0 stays an answer and the 3D error of (r_n, r_t, 0) is the 2D one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "local_problem.h"

struct SolverOptions;  // Siconos numerics' (SolverOptions.h)

namespace peers {

struct SiconosSettings {
  double tolerance = 1e-4;       // the solver's own stopping error (its dparam[SICONOS_DPARAM_TOL])
  int max_iterations = 1000000;  // its iparam[SICONOS_IPARAM_MAX_ITER]
  int dense_rows_limit = 3000;   // solvers that take W dense are refused above this many rows
};

struct SiconosResult {
  std::vector<double> reaction;  // r, 2 per contact
  int iterations = 0;            // the solver's iparam[SICONOS_IPARAM_ITER_DONE]
  int info = -1;                 // 0: the solver reports convergence
  double error = 0.0;            // peers::error of the answer
  double seconds = 0.0;          // the driver's call alone (CPU time of the process)
};

// CPU time of the process (s): what the comparison times, robust to a loaded machine.
double cpu_seconds();

// The solvers that apply to a 2D problem, e.g. "fc2d_nsgs", "fc3d_nsn_ac"; names in
// doc/peers.md. Throws std::invalid_argument for another name.
const std::vector<std::string>& siconos_solver_names();

// The options a solve uses: Siconos's defaults for the solver, then a variant's options
// (bench/peers/siconos_variants.h). Throws std::invalid_argument, in one line, for an unknown
// solver, key or value.
using OptionsPointer = std::unique_ptr<SolverOptions, void (*)(SolverOptions*)>;
OptionsPointer siconos_options(const std::string& solver);

// Solves from `start` (r, 2 per contact) with `solver`, a name or a variant's name. Throws
// std::invalid_argument for an unknown name or a dense solver over the limit.
SiconosResult solve_with_siconos(const LocalProblem& problem, const std::string& solver,
                                 const SiconosSettings& settings, const std::vector<double>& start);

// The one error of the comparison: Siconos's fc2d_compute_error of r on the 2D problem with
// norm |q| (doc/peers.md).
double error(const LocalProblem& problem, const std::vector<double>& reaction);

// |F(r)| over the problem's own scale, max(|q|, |r0|, |W r0 + q|) with r0 the warm start, where
// error() divides by the answer's, max(|r|, |W r + q|, |q|): an answer cannot lower it by growing
// r along W's null space (doc/peers.md, *Results*).
double error_at_problem_scale(const LocalProblem& problem, const std::vector<double>& reaction);

// The same error, measured again and again on one problem (the problem held once).
class ErrorMeter {
 public:
  explicit ErrorMeter(const LocalProblem& problem);
  ~ErrorMeter();
  ErrorMeter(const ErrorMeter&) = delete;
  ErrorMeter& operator=(const ErrorMeter&) = delete;
  double operator()(const std::vector<double>& reaction);

 private:
  struct Held;
  std::unique_ptr<Held> held_;
};

}  // namespace peers
