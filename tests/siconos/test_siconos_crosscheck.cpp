// Cross-check against Siconos numerics' fc2d solvers: the same 2D frictional contact problems
// (W, q, mu), u = W r + q, solved by the core and by an independent implementation, compared
// by both codes' error measures and by the impulses themselves.
//
// Siconos's convention, used for every vector here: per contact [normal, tangent]; the dense
// W is column-major; the Coulomb law is r_t = -mu r_n sign(u_t), as in the core.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "cd/contact_geometry.h"
#include "cd/coulomb_local.h"
#include "cd/gauss_seidel.h"
#include "cd/walls.h"

// fc2d_compute_error.h declares C99 `restrict` parameters.
#define restrict __restrict__
#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "fc2d_compute_error.h"
#undef restrict

extern "C" void dsyev_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda,
                       double* w, double* work, const int* lwork, int* info, std::size_t jobz_len,
                       std::size_t uplo_len);

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

double norm2(const std::vector<double>& x)
{
  double sum = 0.0;
  for (double v : x) sum += v * v;
  return std::sqrt(sum);
}

double distance(const std::vector<double>& x, const std::vector<double>& y)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += (x[i] - y[i]) * (x[i] - y[i]);
  return std::sqrt(sum);
}

// ---------------------------------------------------------------------------------------------
// The problem and the two codes' views of it
// ---------------------------------------------------------------------------------------------

// u = W r + q with 0 <= u_n ⊥ r_n >= 0 and Coulomb's law per contact.
struct Fc2dProblem {
  int contacts = 0;
  std::vector<double> delassus;       // W (m/s per N s), 2m x 2m, column-major
  std::vector<double> free_velocity;  // q (m/s)
  std::vector<double> mu;             // one coefficient per contact

  explicit Fc2dProblem(int contact_count)
      : contacts(contact_count),
        delassus(4 * contact_count * contact_count, 0.0),
        free_velocity(2 * contact_count, 0.0),
        mu(contact_count, 0.0)
  {
  }
  int size() const { return 2 * contacts; }
  double& w(int row, int col) { return delassus[row + col * size()]; }
  double w(int row, int col) const { return delassus[row + col * size()]; }

  std::vector<double> velocity(const std::vector<double>& reaction) const
  {
    std::vector<double> u = free_velocity;
    for (int col = 0; col < size(); ++col)
      for (int row = 0; row < size(); ++row) u[row] += w(row, col) * reaction[col];
    return u;
  }
};

// The problem as Siconos holds it; the matrix is copied into storage Siconos owns and frees.
class SiconosProblem {
 public:
  explicit SiconosProblem(const Fc2dProblem& p) : q_(p.free_velocity), mu_(p.mu)
  {
    matrix_ = NM_create(NM_DENSE, p.size(), p.size());
    std::copy(p.delassus.begin(), p.delassus.end(), matrix_->matrix0);
    problem_.dimension = 2;
    problem_.numberOfContacts = p.contacts;
    problem_.M = matrix_;
    problem_.q = q_.data();
    problem_.mu = mu_.data();
  }
  ~SiconosProblem() { NM_free(matrix_); }
  SiconosProblem(const SiconosProblem&) = delete;
  SiconosProblem& operator=(const SiconosProblem&) = delete;

  FrictionContactProblem* get() { return &problem_; }

 private:
  std::vector<double> q_;
  std::vector<double> mu_;
  NumericsMatrix* matrix_ = nullptr;
  FrictionContactProblem problem_{};
};

struct SiconosSolution {
  std::vector<double> reaction;  // r (N s)
  int info = -1;                 // 0 when the solver reports convergence
  int iterations = 0;
};

SiconosSolution solve_with_siconos(const Fc2dProblem& p, int solver_id, double tolerance,
                                   int max_iterations)
{
  SiconosProblem problem(p);
  std::unique_ptr<SolverOptions, void (*)(SolverOptions*)> options(solver_options_create(solver_id),
                                                                   solver_options_delete);
  options->dparam[SICONOS_DPARAM_TOL] = tolerance;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
  SiconosSolution s;
  s.reaction.assign(p.size(), 0.0);
  std::vector<double> velocity(p.size(), 0.0);
  s.info = fc2d_driver(problem.get(), s.reaction.data(), velocity.data(), options.get());
  s.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  return s;
}

// Siconos's error measure, absolute (norm argument 0): |r - proj_K(r - u_hat)| over all contacts.
double siconos_error(const Fc2dProblem& p, std::vector<double> reaction)
{
  SiconosProblem problem(p);
  std::vector<double> velocity(p.size(), 0.0);
  double error = 0.0;
  fc2d_compute_error(problem.get(), reaction.data(), velocity.data(), 0.0, 0.0, &error);
  return error;
}

// The core's error measure on the same problem: sqrt of the sum of the contacts' squared
// natural-map residuals.
double core_error(const Fc2dProblem& p, const std::vector<double>& reaction)
{
  const std::vector<double> u = p.velocity(reaction);
  double sum = 0.0;
  for (int i = 0; i < p.contacts; ++i)
    sum += cd::natural_map_residual_squared({reaction[2 * i], reaction[2 * i + 1]},
                                            {u[2 * i], u[2 * i + 1]}, p.mu[i]);
  return std::sqrt(sum);
}

// Smallest and largest eigenvalues of a symmetric matrix (column-major, LAPACK dsyev).
struct Spectrum {
  double min = 0.0;
  double max = 0.0;
};

Spectrum symmetric_spectrum(std::vector<double> a, int n)
{
  std::vector<double> eigenvalues(n);
  int lwork = -1, info = 0;
  double query = 0.0;
  dsyev_("N", "U", &n, a.data(), &n, eigenvalues.data(), &query, &lwork, &info, 1, 1);
  lwork = static_cast<int>(query);
  std::vector<double> work(lwork);
  dsyev_("N", "U", &n, a.data(), &n, eigenvalues.data(), work.data(), &lwork, &info, 1, 1);
  EXPECT_EQ(info, 0) << "dsyev failed";
  return {eigenvalues.front(), eigenvalues.back()};
}

// ---------------------------------------------------------------------------------------------
// One contact: the exact local solver against every fc2d solver
// ---------------------------------------------------------------------------------------------

struct SiconosSolver {
  int id;
  const char* name;
  bool through_lcp;  // reformulated as an LCP in the variables (r_n, r_t + mu r_n, ...)
};

const SiconosSolver local_solvers[] = {{SICONOS_FRICTION_2D_NSGS, "NSGS", false},
                                       {SICONOS_FRICTION_2D_LEMKE, "Lemke", true},
                                       {SICONOS_FRICTION_2D_ENUM, "Enum", true}};

// The one-contact problem has a unique solution if u_free.n < 0, or if mu |W_nt| < W_nn.
// Proof: if u_free.n < 0 then r_n > 0 and u_n = 0; on that line u_t is strictly increasing in
// r_t (slope det W / W_nn), and the cone cuts the line in an interval bounded by the edges
// whose normal stiffness W_nn -/+ mu W_nt is positive; the edge with a non-positive stiffness
// is never reached, so Coulomb's law is a monotone variational inequality in r_t on that
// interval: one solution. If u_free.n >= 0, r = 0 is a solution, and any other has r_n > 0
// and u_n = u_free.n + W_nn r_n + W_nt r_t >= (W_nn - mu |W_nt|) r_n > 0: none when
// mu |W_nt| < W_nn. Otherwise a second solution exists for suitable u_free (r on the edge of
// negative stiffness, closing the gap), so only residuals are compared.
bool local_solution_is_unique(const cd::Delassus2& w, cd::Local2 u_free, double mu)
{
  return u_free.n < 0.0 || mu * std::abs(w.nt) < w.nn;
}

TEST(SiconosLocal, ExactLocalSolverAgreesWithFc2dSolvers)
{
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double mus[] = {0.0, 0.05, 0.5, 2.0, 1e6};
  const int cases_per_mu = 400;

  int compared = 0, residual_only = 0;
  int status_count[4] = {0, 0, 0, 0};
  int attempts[3] = {0, 0, 0}, rejected[3] = {0, 0, 0};
  double worst_impulse[3] = {0, 0, 0}, worst_residual[3] = {0, 0, 0}, worst_ours = 0;
  for (double mu : mus) {
    for (int k = 0; k < cases_per_mu; ++k) {
      cd::Delassus2 w;
      w.nn = 0.5 + 3.5 * unit(rng);
      w.tt = 0.5 + 3.5 * unit(rng);
      const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
      const double coupling_bound = 0.8 * std::sqrt(w.nn * w.tt);  // det W >= 0.36 W_nn W_tt
      switch (k % 3) {
        case 0: w.nt = 0.0; break;  // a disk: the normal passes through both centres
        case 1:                     // coupled, but unique for this mu: mu |W_nt| <= 0.8 W_nn
          w.nt = sign * unit(rng) * std::min(coupling_bound, mu > 0.0 ? 0.8 * w.nn / mu : coupling_bound);
          break;
        default:  // coupled, unique or not; sliding normal stiffness W_nn -/+ mu W_nt >= 0.1 W_nn
          do w.nt = sign * unit(rng) * coupling_bound;
          while (std::abs(std::abs(mu * w.nt) - w.nn) < 0.1 * w.nn);
      }
      const cd::Local2 u_free{-1.0 + 1.5 * unit(rng), -1.5 + 3.0 * unit(rng)};

      Fc2dProblem p(1);
      p.w(0, 0) = w.nn;
      p.w(0, 1) = p.w(1, 0) = w.nt;
      p.w(1, 1) = w.tt;
      p.free_velocity = {u_free.n, u_free.t};
      p.mu = {mu};

      const cd::LocalSolution ours = cd::solve_coulomb_local(w, u_free, mu);
      const std::vector<double> r_ours = {ours.impulse.n, ours.impulse.t};

      const double lambda_min = 0.5 * (w.nn + w.tt) - std::sqrt(0.25 * (w.nn - w.tt) * (w.nn - w.tt) + w.nt * w.nt);
      const double w_norm = w.nn + w.tt - lambda_min;
      const double sliding_stiffness = std::min(std::abs(w.nn - mu * w.nt), std::abs(w.nn + mu * w.nt));
      const double amplify = w_norm / lambda_min + (w.nn + mu * std::abs(w.nt)) / sliding_stiffness;
      const double impulse_scale = std::hypot(r_ours[0], r_ours[1]) + std::hypot(u_free.n, u_free.t) / lambda_min;
      const double velocity_scale = std::hypot(u_free.n, u_free.t) + w_norm * impulse_scale;
      const double direct_tol = eps * amplify * impulse_scale;
      const double lcp_tol = direct_tol + eps * mu * impulse_scale;
      const double direct_residual_tol = direct_tol + (1.0 + mu) * (eps * velocity_scale + w_norm * direct_tol);
      const double lcp_residual_tol = lcp_tol + (1.0 + mu) * (eps * velocity_scale + w_norm * lcp_tol);

      const double ours_by_core = core_error(p, r_ours);
      const double ours_by_siconos = siconos_error(p, r_ours);
      EXPECT_LE(ours_by_core, 64 * direct_residual_tol) << "mu " << mu << " case " << k;
      EXPECT_LE(ours_by_siconos, 64 * direct_residual_tol) << "mu " << mu << " case " << k;
      worst_ours = std::max(worst_ours, ours_by_core / direct_residual_tol);

      const bool unique = local_solution_is_unique(w, u_free, mu);
      if (unique) {
        ++compared;
        ++status_count[static_cast<int>(ours.status)];
      } else {
        ++residual_only;
      }
      for (int s = 0; s < 3; ++s) {
        const SiconosSolver& solver = local_solvers[s];
        if (solver.through_lcp && mu > 100.0) continue;
        ++attempts[s];
        const SiconosSolution theirs = solve_with_siconos(p, solver.id, 1e-14, 100);
        const double impulse_tol = solver.through_lcp ? lcp_tol : direct_tol;
        const double residual_tol = solver.through_lcp ? lcp_residual_tol : direct_residual_tol;
        const double theirs_by_siconos = siconos_error(p, theirs.reaction);
        const double theirs_by_core = core_error(p, theirs.reaction);
        EXPECT_NEAR(theirs_by_core, theirs_by_siconos, 16 * eps * (1.0 + mu) * velocity_scale);
        if (theirs_by_siconos > 64 * residual_tol) {
          ++rejected[s];
          continue;
        }
        worst_residual[s] = std::max(worst_residual[s], theirs_by_core / residual_tol);
        if (!unique) continue;
        const double gap = distance(r_ours, theirs.reaction);
        EXPECT_LE(gap, 64 * impulse_tol) << solver.name << " mu " << mu << " case " << k << " W = ("
                                    << w.nn << ", " << w.nt << ", " << w.tt << ") u_free = ("
                                    << u_free.n << ", " << u_free.t << ") ours ("
                                    << r_ours[0] << ", " << r_ours[1] << ") theirs ("
                                    << theirs.reaction[0] << ", " << theirs.reaction[1] << ")";
        worst_impulse[s] = std::max(worst_impulse[s], gap / impulse_tol);
      }
    }
  }
  std::printf("local: %d compared, %d residual only; statuses none/stick/slip+/slip- %d/%d/%d/%d\n",
              compared, residual_only, status_count[0], status_count[1], status_count[2],
              status_count[3]);
  for (int s = 0; s < 3; ++s)
    std::printf("local %s: %d solved, %d rejected, worst impulse gap/tol %.3g, worst residual/tol %.3g\n",
                local_solvers[s].name, attempts[s], rejected[s], worst_impulse[s], worst_residual[s]);
  std::printf("ours worst residual/tol %.3g\n", worst_ours);
  for (int s = 0; s < 4; ++s) EXPECT_GE(status_count[s], 50) << "status " << s;
  EXPECT_GE(compared, 4 * residual_only);
}

}  // namespace
