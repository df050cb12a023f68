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
#include <iterator>
#include <limits>
#include <memory>
#include <random>
#include <tuple>
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

extern "C" void dsyev_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w,
                       double* work, const int* lwork, int* info, std::size_t jobz_len, std::size_t uplo_len);

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

SiconosSolution solve_with_siconos(const Fc2dProblem& p, int solver_id, double tolerance, int max_iterations)
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

// Siconos's error measure. fc2d_compute_error (4.4) returns the natural-map residual
// |r - proj_K(r - u_hat)| divided by max(|r|, |u|, norm), norm = 0 here; it is multiplied back
// by that scale so that one absolute tolerance serves both codes.
double siconos_error(const Fc2dProblem& p, std::vector<double> reaction)
{
  SiconosProblem problem(p);
  std::vector<double> velocity(p.size(), 0.0);
  double relative_error = 0.0;
  fc2d_compute_error(problem.get(), reaction.data(), velocity.data(), 0.0, 0.0, &relative_error);
  const double scale = std::max(norm2(reaction), norm2(p.velocity(reaction)));
  return scale > std::numeric_limits<double>::epsilon() ? relative_error * scale : relative_error;
}

// The core's error measure on the same problem: sqrt of the sum of the contacts' squared
// natural-map residuals.
double core_error(const Fc2dProblem& p, const std::vector<double>& reaction)
{
  const std::vector<double> u = p.velocity(reaction);
  double sum = 0.0;
  for (int i = 0; i < p.contacts; ++i)
    sum += cd::natural_map_residual_squared({reaction[2 * i], reaction[2 * i + 1]}, {u[2 * i], u[2 * i + 1]}, p.mu[i]);
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

// Siconos's solution is taken when it passes Siconos's own error measure at the rounding
// tolerance of the case; the LCP-based solvers of 4.4 sometimes return a non-solution: Lemke
// ends on a ray (e.g. mu = 0, r = 0 returned for u_free.n < 0) and Enum accepts a singular
// basis whose LU factorisation "succeeded" with 1e15 entries. Such rejections are Siconos's
// failures and are counted; NSGS must never be rejected.
TEST(SiconosLocal, ExactLocalSolverAgreesWithFc2dSolvers)
{
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double mus[] = {0.0, 0.05, 0.5, 2.0, 1e6};
  const int cases_per_mu = 400;

  int compared = 0, residual_only = 0;
  int status_count[4] = {0, 0, 0, 0};
  int attempts[3] = {0, 0, 0}, rejected[3] = {0, 0, 0};
  double worst_gap[3] = {0.0, 0.0, 0.0};  // in units of the rounding model
  for (double mu : mus) {
    for (int k = 0; k < cases_per_mu; ++k) {
      cd::Delassus2 w;
      w.nn = 0.5 + 3.5 * unit(rng);
      w.tt = 0.5 + 3.5 * unit(rng);
      const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
      const double coupling_bound = 0.8 * std::sqrt(w.nn * w.tt);  // det W >= 0.36 W_nn W_tt
      switch (k % 3) {
        case 0: w.nt = 0.0; break;  // a disk: the normal passes through both centres
        case 1:                     // coupled, unique for any u_free: mu |W_nt| <= 0.8 W_nn
          w.nt = sign * unit(rng) * std::min(coupling_bound, mu > 0.0 ? 0.8 * w.nn / mu : coupling_bound);
          break;
        default:  // coupled, unique or not; sliding normal stiffness |W_nn -/+ mu W_nt| >= 0.1 W_nn
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

      // Rounding model. The core and Siconos's NSGS solve the same 2x2 system (stick: error
      // ~ eps cond(W)) or divide by a sliding stiffness W_nn -/+ mu W_nt (error ~ eps
      // (W_nn + mu |W_nt|) / |stiffness|); `amplify`, their sum, is below 60 by construction.
      // The LCP reformulation (Lemke, Enum) carries r_t + mu r_n and mu r_n - r_t and returns
      // r_t as half their difference: eps mu |r| more. The natural map sees an error e in r
      // directly, and one in u = W r + q through u_n + mu |u_t|: (1 + mu)(eps V + |W| e).
      // Every check allows 64 times the model (the worst case seen is 1.5 times: Lemke's
      // impulses; the core and NSGS agree to the last bit).
      const double lambda_min = 0.5 * (w.nn + w.tt) - std::hypot(0.5 * (w.nn - w.tt), w.nt);
      const double w_norm = w.nn + w.tt - lambda_min;
      const double sliding_stiffness = std::min(std::abs(w.nn - mu * w.nt), std::abs(w.nn + mu * w.nt));
      const double amplify = w_norm / lambda_min + (w.nn + mu * std::abs(w.nt)) / sliding_stiffness;
      const double impulse_scale = std::hypot(r_ours[0], r_ours[1]) + std::hypot(u_free.n, u_free.t) / lambda_min;
      const double velocity_scale = std::hypot(u_free.n, u_free.t) + w_norm * impulse_scale;
      auto impulse_rounding = [&](bool through_lcp) {
        return eps * (amplify + (through_lcp ? mu : 0.0)) * impulse_scale;
      };
      auto residual_rounding = [&](bool through_lcp) {
        const double e = impulse_rounding(through_lcp);
        return e + (1.0 + mu) * (eps * velocity_scale + w_norm * e);
      };

      EXPECT_LE(core_error(p, r_ours), 64.0 * residual_rounding(false)) << "mu " << mu << " case " << k;
      EXPECT_LE(siconos_error(p, r_ours), 64.0 * residual_rounding(false)) << "mu " << mu << " case " << k;

      const bool unique = local_solution_is_unique(w, u_free, mu);
      if (unique) {
        ++compared;
        ++status_count[static_cast<int>(ours.status)];
      } else {
        ++residual_only;
      }
      for (int s = 0; s < 3; ++s) {
        const SiconosSolver& solver = local_solvers[s];
        // At mu = 1e6 the LCP's own rounding, eps mu |r| in r_t, reaches the residual as
        // eps mu^2 ~ 1e-4: beyond any error measure, so only NSGS is compared there.
        if (solver.through_lcp && mu > 100.0) continue;
        ++attempts[s];
        const SiconosSolution theirs = solve_with_siconos(p, solver.id, 1e-14, 100);
        const double theirs_by_core = core_error(p, theirs.reaction);
        const double theirs_by_siconos = siconos_error(p, theirs.reaction);
        // The same natural map in both codes, up to the rounding of u = W r + q.
        EXPECT_NEAR(theirs_by_core, theirs_by_siconos, 16.0 * eps * (1.0 + mu) * velocity_scale)
            << solver.name << " mu " << mu << " case " << k;
        if (theirs_by_siconos > 64.0 * residual_rounding(solver.through_lcp)) {
          ++rejected[s];
          continue;
        }
        if (!unique) continue;
        const double gap = distance(r_ours, theirs.reaction);
        EXPECT_LE(gap, 64.0 * impulse_rounding(solver.through_lcp))
            << solver.name << " mu " << mu << " case " << k << ": W = (" << w.nn << ", " << w.nt << ", " << w.tt
            << "), u_free = (" << u_free.n << ", " << u_free.t << "), core (" << r_ours[0] << ", " << r_ours[1]
            << "), Siconos (" << theirs.reaction[0] << ", " << theirs.reaction[1] << ")";
        worst_gap[s] = std::max(worst_gap[s], gap / impulse_rounding(solver.through_lcp));
      }
    }
  }
  EXPECT_EQ(rejected[0], 0);
  // Lemke's and Enum's own accuracy depends on the LAPACK kernel OpenBLAS picks for the CPU
  // (Enum: under 1 in 50 rejected on the machines this was first run on, 81 of 1600 on an AMD
  // EPYC with OpenBLAS 0.3.21); nine in ten must still be compared.
  for (int s = 1; s < 3; ++s) EXPECT_LE(rejected[s], attempts[s] / 10) << local_solvers[s].name;
  // Every branch of the Coulomb graph is compared, and most cases are unique.
  for (int s = 0; s < 4; ++s) EXPECT_GE(status_count[s], 50) << "status " << s;
  EXPECT_GE(compared, 4 * residual_only);
  std::printf(
      "one contact: %d unique cases compared (no contact/stick/slip+/slip- %d/%d/%d/%d), "
      "%d compared by residuals only\n",
      compared, status_count[0], status_count[1], status_count[2], status_count[3], residual_only);
  for (int s = 0; s < 3; ++s)
    std::printf("  %-5s %4d solved, %d rejected by Siconos's own error, worst impulse gap %.2g x model\n",
                local_solvers[s].name, attempts[s], rejected[s], worst_gap[s]);
}

// ---------------------------------------------------------------------------------------------
// Many contacts: Gauss–Seidel on a disk cluster against fc2d solvers on the assembled problem
// ---------------------------------------------------------------------------------------------

// A contact as the test derives it from the disks alone.
struct ContactKinematics {
  int body_a = 0;
  int body_b = 0;   // cd::world_body for a wall
  double nx = 0.0;  // unit normal from b to a
  double ny = 0.0;
  double lever_a = 0.0;  // centre-to-contact distances (m); 0 for the world
  double lever_b = 0.0;
};

struct Scene {
  std::vector<cd::Disk> disks;  // indexed by body; disks[0] stands for the world
  std::vector<ContactKinematics> kinematics;
  std::vector<cd::Contact> contacts;
  std::vector<double> gaps;  // of the contacts (m)
  cd::BodySet bodies;
  int body_count() const { return static_cast<int>(disks.size()) - 1; }  // the world excluded
};

// Disks of radius U[0.4, 0.6] dropped one by one against the cluster, each overlapping one
// placed disk, or with probability `nest_probability` two (a nest, closing a loop of
// contacts), by 1e-6..1e-3 m, and no other disk by more: every contact has gap < 0, an impact,
// so zero restitution leaves no velocity bias and q is the free relative velocity.
std::vector<cd::Disk> random_cluster(int count, double nest_probability, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto overlap = [&] { return 1e-6 + (1e-3 - 1e-6) * unit(rng); };
  std::vector<cd::Disk> disks(1);
  disks.push_back({0.0, 0.0, 0.4 + 0.2 * unit(rng)});
  while (static_cast<int>(disks.size()) <= count) {
    cd::Disk d{0.0, 0.0, 0.4 + 0.2 * unit(rng)};
    const int placed = static_cast<int>(disks.size()) - 1;
    const cd::Disk& p = disks[1 + static_cast<int>(unit(rng) * placed) % placed];
    int nest = 0;  // a second disk to touch, if any is close enough
    if (placed > 1 && unit(rng) < nest_probability) {
      double best = std::numeric_limits<double>::infinity();
      for (int j = 1; j <= placed; ++j) {
        const double dist = std::hypot(disks[j].x - p.x, disks[j].y - p.y);
        if (dist > 0.0 && dist < best) best = dist, nest = j;
      }
    }
    if (nest) {
      const cd::Disk& q = disks[nest];
      const double a = p.radius + d.radius - overlap(), b = q.radius + d.radius - overlap();
      const double ex = q.x - p.x, ey = q.y - p.y, dist = std::hypot(ex, ey);
      if (dist >= a + b) continue;
      const double along = (a * a - b * b + dist * dist) / (2.0 * dist);
      const double side = (unit(rng) < 0.5 ? -1.0 : 1.0) * std::sqrt(a * a - along * along);
      d.x = p.x + (along * ex - side * ey) / dist;
      d.y = p.y + (along * ey + side * ex) / dist;
    } else {
      const double angle = 2.0 * M_PI * unit(rng);
      const double dist = p.radius + d.radius - overlap();
      d.x = p.x + dist * std::cos(angle);
      d.y = p.y + dist * std::sin(angle);
    }
    bool fits = true;
    for (int j = 1; j <= placed && fits; ++j)
      fits = std::hypot(d.x - disks[j].x, d.y - disks[j].y) - d.radius - disks[j].radius >= -1e-3;
    if (fits) disks.push_back(d);
  }
  return disks;
}

// Zero restitution and a step that only enters through the impact test (gap < 0 here).
const cd::StepParameters scene_step{1e-3, 0.5};

// The cluster on a floor and against a left wall (both overlapping their nearest disks by
// 5e-4 m), bodies with m = pi r^2, I = m r^2 / 2 and a free velocity that compresses the
// cluster towards its centre and the floor, plus noise and spin.
Scene random_scene(int disk_count, double nest_probability, double mu, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Scene s;
  s.disks = random_cluster(disk_count, nest_probability, rng);
  const int n = s.body_count();

  s.bodies.reset(n + 1);
  double cx = 0.0, cy = 0.0;
  for (int i = 1; i <= n; ++i) cx += s.disks[i].x / n, cy += s.disks[i].y / n;
  for (int i = 1; i <= n; ++i) {
    const cd::Disk& d = s.disks[i];
    const double mass = M_PI * d.radius * d.radius;
    s.bodies.inertia[i] = {1.0 / mass, 1.0 / (0.5 * mass * d.radius * d.radius)};
    s.bodies.velocity[i] = {-0.3 * (d.x - cx) + (2.0 * unit(rng) - 1.0),
                            -0.3 * (d.y - cy) - 0.5 + (2.0 * unit(rng) - 1.0), 4.0 * unit(rng) - 2.0};
  }
  s.bodies.start_velocity = s.bodies.velocity;

  const cd::ContactLaw law{mu, 0.0};
  auto add = [&](const cd::ContactGeometry& g, const ContactKinematics& k) {
    s.contacts.push_back(cd::prepared_contact(g, law, s.bodies, scene_step));
    s.gaps.push_back(g.gap);
    s.kinematics.push_back(k);
  };
  for (int i = 1; i <= n; ++i)
    for (int j = i + 1; j <= n; ++j) {
      const bool flip = unit(rng) < 0.5;  // either disk may be body a
      const int a = flip ? j : i, b = flip ? i : j;
      const cd::Disk &da = s.disks[a], &db = s.disks[b];
      const double dist = std::hypot(da.x - db.x, da.y - db.y);
      if (dist - da.radius - db.radius >= 0.0) continue;
      add(cd::disk_disk_geometry(a, da, b, db),
          {a, b, (da.x - db.x) / dist, (da.y - db.y) / dist, da.radius, db.radius});
    }
  double floor_y = std::numeric_limits<double>::infinity(), wall_x = floor_y;
  for (int i = 1; i <= n; ++i) {
    floor_y = std::min(floor_y, s.disks[i].y - s.disks[i].radius + 5e-4);
    wall_x = std::min(wall_x, s.disks[i].x - s.disks[i].radius + 5e-4);
  }
  for (int i = 1; i <= n; ++i) {
    const cd::Disk& d = s.disks[i];
    if (d.y - d.radius < floor_y)
      add(cd::disk_world_geometry(i, d, 0.0, d.y - floor_y, 0.0, 1.0), {i, cd::world_body, 0.0, 1.0, d.radius, 0.0});
    if (d.x - d.radius < wall_x)
      add(cd::disk_world_geometry(i, d, d.x - wall_x, 0.0, 1.0, 0.0), {i, cd::world_body, 1.0, 0.0, d.radius, 0.0});
  }
  return s;
}

// Prepares the scene's contacts again with another friction coefficient.
void set_friction(Scene& s, double mu)
{
  for (std::size_t k = 0; k < s.contacts.size(); k++)
    cd::prepare_mechanics(s.contacts[k], s.gaps[k], {mu, 0.0}, s.bodies, scene_step);
}

// H, the 2m x 3N map from body velocities (vx, vy, spin of bodies 1..N) to contact velocities,
// row-major, from the kinematics of rigid disks: the contact point of a is c_a = x_a - r_a n,
// of b is x_b + r_b n, and omega x (-r n) = -r omega t with t = (-n_y, n_x), so
//   u_n = (v_a - v_b) . n,   u_t = (v_a - v_b) . t - r_a omega_a - r_b omega_b.
std::vector<double> contact_jacobian(const Scene& s)
{
  const int m = static_cast<int>(s.kinematics.size()), cols = 3 * s.body_count();
  std::vector<double> h(2 * m * cols, 0.0);
  for (int k = 0; k < m; ++k) {
    const ContactKinematics& c = s.kinematics[k];
    const double tx = -c.ny, ty = c.nx;
    double* normal = &h[(2 * k) * cols];
    double* tangent = &h[(2 * k + 1) * cols];
    const int a = 3 * (c.body_a - 1);
    normal[a] += c.nx, normal[a + 1] += c.ny;
    tangent[a] += tx, tangent[a + 1] += ty, tangent[a + 2] -= c.lever_a;
    if (c.body_b != cd::world_body) {
      const int b = 3 * (c.body_b - 1);
      normal[b] -= c.nx, normal[b + 1] -= c.ny;
      tangent[b] -= tx, tangent[b + 1] -= ty, tangent[b + 2] -= c.lever_b;
    }
  }
  return h;
}

std::vector<double> generalized(const std::vector<cd::BodyVelocity>& v)
{
  std::vector<double> g;
  for (std::size_t i = 1; i < v.size(); ++i) g.insert(g.end(), {v[i].vx, v[i].vy, v[i].spin});
  return g;
}

std::vector<double> times(const std::vector<double>& matrix, int rows, const std::vector<double>& x)
{
  const int cols = static_cast<int>(x.size());
  std::vector<double> y(rows, 0.0);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) y[i] += matrix[i * cols + j] * x[j];
  return y;
}

// W = H M^-1 H^T and q = H v_free, assembled independently of the core's contact blocks.
// One mu for all contacts: Siconos 4.4's fc2d_tolcp builds the off-diagonal blocks of its LCP
// with the row contact's mu where the column contact's belongs, so Lemke and Enum solve
// another problem when the coefficients differ.
Fc2dProblem assemble(const Scene& s, const std::vector<double>& h, double mu)
{
  const int m = static_cast<int>(s.contacts.size()), cols = 3 * s.body_count();
  std::vector<double> inverse_mass(cols);
  for (int i = 1; i <= s.body_count(); ++i) {
    inverse_mass[3 * (i - 1)] = inverse_mass[3 * (i - 1) + 1] = s.bodies.inertia[i].inv_mass;
    inverse_mass[3 * (i - 1) + 2] = s.bodies.inertia[i].inv_inertia;
  }
  Fc2dProblem p(m);
  for (int i = 0; i < 2 * m; ++i)
    for (int j = 0; j < 2 * m; ++j) {
      double sum = 0.0;
      for (int k = 0; k < cols; ++k) sum += h[i * cols + k] * inverse_mass[k] * h[j * cols + k];
      p.w(i, j) = sum;
    }
  p.free_velocity = times(h, 2 * m, generalized(s.bodies.velocity));
  p.mu.assign(m, mu);
  return p;
}

// The solver core's run on a scene: Gauss–Seidel from zero impulses, as the driver runs it.
struct CoreRun {
  cd::SolveReport report;
  std::vector<double> reaction;       // r (N s), per contact [normal, tangent]
  std::vector<double> body_velocity;  // u from the bodies' final velocities (m/s)
};

// How the core's sweeps run, besides plain Gauss–Seidel: the ways of needing fewer local solves.
struct SweepVariant {
  const char* name;
  cd::Acceleration acceleration;
  int full_sweep_every;
};
constexpr SweepVariant plain_sweeps{"plain", cd::Acceleration::none, 1};
constexpr SweepVariant faster_sweeps[] = {{"conjugate", cd::Acceleration::conjugate, 1},
                                          {"cycles of 8", cd::Acceleration::none, 8},
                                          {"conjugate in cycles of 8", cd::Acceleration::conjugate, 8}};

CoreRun run_core(Scene scene, double tolerance, int max_sweeps, SweepVariant variant = plain_sweeps)
{
  std::vector<cd::BodyVelocity> velocity = scene.bodies.velocity;
  cd::apply_impulses(scene.contacts, velocity);  // the (zero) warm start
  cd::SolverSettings settings;
  settings.tolerance = tolerance;
  settings.max_iterations = max_sweeps;
  settings.gauss_seidel.acceleration = variant.acceleration;
  settings.gauss_seidel.full_sweep_every = variant.full_sweep_every;
  CoreRun run;
  run.report = cd::solve_gauss_seidel(scene.contacts, velocity, settings);
  for (const cd::Contact& c : scene.contacts) {
    const cd::Local2 u = cd::relative_velocity(c, velocity[c.body_a], velocity[c.body_b]);
    run.reaction.insert(run.reaction.end(), {c.impulse.n, c.impulse.t});
    run.body_velocity.insert(run.body_velocity.end(), {u.n, u.t});
  }
  return run;
}

// What the tolerances of one scene are made of.
struct SceneScales {
  Spectrum delassus;             // eigenvalues of W
  double frobenius = 0.0;        // |W|_F, bounds the strictly upper block triangle of W
  double tangential = 0.0;       // |W_T|_2, W_T the tangential rows of W
  double local_condition = 0.0;  // max over contacts of the largest eigenvalue of W_ii / min of the smallest
  double impulse = 0.0;          // P (N s)
  double velocity = 0.0;         // V (m/s)
};

SceneScales scene_scales(const Fc2dProblem& p, const std::vector<double>& reaction)
{
  SceneScales s;
  const int m = p.contacts;
  s.delassus = symmetric_spectrum(p.delassus, 2 * m);
  s.frobenius = norm2(p.delassus);
  std::vector<double> gram(m * m, 0.0);  // W_T W_T^T
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int l = 0; l < 2 * m; ++l) gram[i + j * m] += p.w(2 * i + 1, l) * p.w(2 * j + 1, l);
  s.tangential = std::sqrt(symmetric_spectrum(gram, m).max);
  double local_max = 0.0, local_min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m; ++i) {
    const Spectrum block = symmetric_spectrum(
        {p.w(2 * i, 2 * i), p.w(2 * i + 1, 2 * i), p.w(2 * i, 2 * i + 1), p.w(2 * i + 1, 2 * i + 1)}, 2);
    local_max = std::max(local_max, block.max);
    local_min = std::min(local_min, block.min);
  }
  s.local_condition = local_max / local_min;
  s.impulse = std::max(norm2(reaction), norm2(p.free_velocity) / s.delassus.max);
  s.velocity = norm2(p.free_velocity) + s.delassus.max * s.impulse;
  return s;
}

// Checks shared by every scene: the test's H and W against the core's kinematics and blocks,
// and the core's body velocities against u = W r + q.
void check_assembly(const Scene& scene, const std::vector<double>& h, const Fc2dProblem& p, const CoreRun& run,
                    const SceneScales& scales, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int m = p.contacts;
  std::vector<cd::BodyVelocity> probe(scene.body_count() + 1);
  for (int i = 1; i <= scene.body_count(); ++i) probe[i] = {unit(rng), unit(rng), unit(rng)};
  const std::vector<double> u_probe = times(h, 2 * m, generalized(probe));
  // A handful of O(1) products: rounding is a few eps.
  const double rounding = 64.0 * eps;
  for (int c = 0; c < m; ++c) {
    const cd::Contact& contact = scene.contacts[c];
    const cd::Local2 u = cd::relative_velocity(contact, probe[contact.body_a], probe[contact.body_b]);
    EXPECT_NEAR(u.n, u_probe[2 * c], rounding) << "contact " << c;
    EXPECT_NEAR(u.t, u_probe[2 * c + 1], rounding) << "contact " << c;
    const double block_scale = p.w(2 * c + 1, 2 * c + 1);
    EXPECT_NEAR(contact.delassus.nn, p.w(2 * c, 2 * c), rounding * block_scale) << "contact " << c;
    EXPECT_NEAR(0.0, p.w(2 * c, 2 * c + 1), rounding * block_scale) << "contact " << c;  // disks: W_nt = 0
    EXPECT_NEAR(contact.delassus.tt, p.w(2 * c + 1, 2 * c + 1), rounding * block_scale) << "contact " << c;
  }
  // The bodies' velocities accumulate one rounding per applied increment: a random walk of
  // about sqrt(sweeps x contacts per body) steps of eps V, under 1e-13 V for 2e4 sweeps.
  EXPECT_LE(distance(run.body_velocity, p.velocity(run.reaction)), 1e-12 * scales.velocity);
}

constexpr double gauss_seidel_tolerance = 1e-12;
constexpr int max_sweeps = 20000;

// A priori bounds on the natural-map residual R of each code's stopped iterate, from its own
// stopping rule. At its last update each contact solved its local problem exactly, at the
// velocity v_i of that moment; the contacts updated after it moved its velocity by delta_i,
// and R_i <= |u_hat(v_i + delta_i) - u_hat(v_i)| <= (1 + mu) |delta_i| (the projection is
// non-expansive).
//  - Core: delta = strict upper block triangle of W times the last sweep's change dp, so
//    |delta| <= |W|_F |dp|, and the quadratic norm |W_ii dp| / |W_ii p| <= tol gives
//    |dp| <= local condition x tol x |r|.
//  - Siconos NSGS: it stops when |q + W r - v| <= tol |q|, v the velocities of the updates:
//    that is |delta| itself.
// Rounding adds about eps (1 + mu) (P + V) per contact; 1e3 eps covers it.
double core_residual_bound(const SceneScales& s, double mu)
{
  return (1.0 + mu) *
         (s.frobenius * s.local_condition * gauss_seidel_tolerance * s.impulse + 1e3 * eps * (s.impulse + s.velocity));
}

double nsgs_residual_bound(const SceneScales& s, const Fc2dProblem& p, double mu)
{
  return (1.0 + mu) * (gauss_seidel_tolerance * norm2(p.free_velocity) + 1e3 * eps * (s.impulse + s.velocity));
}

// Both codes measure the same natural map; they differ by rounding of u = W r + q, which
// De Saxce's term counts (1 + mu) times.
void expect_same_measure(const Fc2dProblem& p, const std::vector<double>& reaction, const SceneScales& s, double mu,
                         const char* what)
{
  EXPECT_NEAR(core_error(p, reaction), siconos_error(p, reaction), 1e3 * eps * (1.0 + mu) * (s.impulse + s.velocity))
      << what;
}

// Lemke's solution is taken when it passes Siconos's own check at Siconos's default fc2d
// tolerance, 1e-6 relative to max(|r|, |u|): pivoting on the LCP reformulation sometimes ends
// on a ray and returns a non-solution with info = 0 (fc2d_lexicolemke in 4.4 compares the
// error with iparam[SICONOS_DPARAM_TOL], the iteration cap, so info does not tell).
bool lemke_accepted(const Fc2dProblem& p, const std::vector<double>& reaction)
{
  const double scale = std::max(norm2(reaction), norm2(p.velocity(reaction)));
  return siconos_error(p, reaction) <= 1e-6 * scale;
}

// Scenes whose problem is unique (strongly monotone, below): every solver must find the same
// impulses. Tree-like clusters (no nests) keep 2m < 3N, so W = H M^-1 H^T is positive
// definite, and friction is set at half the certified bound.
//
// Uniqueness and an error bound. Coulomb's law is the variational inequality r in K,
// G(r) . (s - r) >= 0 for s in K, with G(r) = u_hat = u + mu |u_t| e_n and u = W r + q
// (De Saxce). For two impulses r, s:
//   (r - s) . (G(r) - G(s)) >= lambda_min |r - s|^2 - mu |r_n - s_n| |W_T (r - s)|
//                           >= c |r - s|^2,   c = lambda_min(W) - mu |W_T|_2,
// and |G(r) - G(s)| <= L |r - s|, L = lambda_max(W) + mu |W_T|_2. If c > 0 the solution r* is
// unique and any r satisfies |r - r*| <= (1 + L) / c R(r), R the natural-map residual (write
// the projection's inequality for y = proj_K(r - G(r)) at r*, and the inequality at r* at y).
// Two codes' answers thus agree within (1 + L) / c (R_1 + R_2), each R bounded a priori by the
// code's stopping rule; R is computed with rounding, 1e3 eps (1 + mu)(P + V) as elsewhere.
TEST(SiconosScene, UniqueProblemsGiveTheSameImpulsesInBothCodes)
{
  std::mt19937_64 rng(1234567);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int scenes = 12;
  int lemke_rejected = 0;
  double plain_updates = 0.0, variant_updates[std::size(faster_sweeps)] = {};
  double worst_gap = 0.0;
  for (int k = 0; k < scenes; ++k) {
    const int disk_count = 5 + static_cast<int>(36 * unit(rng));
    Scene scene;
    Fc2dProblem p(0);
    std::vector<double> h;
    Spectrum spectrum;
    do {  // an accidental loop can make W singular: draw again
      scene = random_scene(disk_count, 0.0, 0.0, rng);
      h = contact_jacobian(scene);
      p = assemble(scene, h, 0.0);
      spectrum = symmetric_spectrum(p.delassus, p.size());
    } while (spectrum.min < 1e-6 * spectrum.max);

    // Half the scenes frictionless, half with friction at half the certified bound.
    double mu = 0.0;
    if (k % 2) {
      const SceneScales s = scene_scales(p, std::vector<double>(p.size(), 0.0));
      mu = 0.5 * s.delassus.min / s.tangential;
      set_friction(scene, mu);
      p.mu.assign(p.contacts, mu);
    }

    const CoreRun ours = run_core(scene, gauss_seidel_tolerance, max_sweeps);
    const SceneScales s = scene_scales(p, ours.reaction);
    check_assembly(scene, h, p, ours, s, rng);
    ASSERT_TRUE(ours.report.converged) << "scene " << k;

    const double monotonicity = s.delassus.min - mu * s.tangential;
    const double lipschitz = s.delassus.max + mu * s.tangential;
    ASSERT_GT(monotonicity, 0.0);
    const double amplification = (1.0 + lipschitz) / monotonicity;

    const double r_ours = core_error(p, ours.reaction);
    EXPECT_LE(r_ours, core_residual_bound(s, mu)) << "scene " << k;
    expect_same_measure(p, ours.reaction, s, mu, "core solution");

    const SiconosSolution nsgs = solve_with_siconos(p, SICONOS_FRICTION_2D_NSGS, gauss_seidel_tolerance, max_sweeps);
    EXPECT_EQ(nsgs.info, 0) << "scene " << k;
    const double r_nsgs = core_error(p, nsgs.reaction);
    EXPECT_LE(r_nsgs, nsgs_residual_bound(s, p, mu)) << "scene " << k;
    expect_same_measure(p, nsgs.reaction, s, mu, "NSGS solution");

    const SiconosSolution lemke =
        solve_with_siconos(p, SICONOS_FRICTION_2D_LEMKE, gauss_seidel_tolerance, 100 * p.size());
    const bool lemke_ok = lemke_accepted(p, lemke.reaction);
    lemke_rejected += !lemke_ok;
    const double r_lemke = core_error(p, lemke.reaction);
    expect_same_measure(p, lemke.reaction, s, mu, "Lemke solution");

    const std::vector<double> u_ours = p.velocity(ours.reaction);
    for (const auto& [name, theirs, residual] :
         {std::tuple{"NSGS", &nsgs, r_nsgs}, std::tuple{"Lemke", &lemke, r_lemke}}) {
      if (theirs == &lemke && !lemke_ok) continue;
      const double rounding = 1e3 * eps * (1.0 + mu) * (s.impulse + s.velocity);
      const double impulse_tol = amplification * (r_ours + residual + 2.0 * rounding);
      const double gap = distance(ours.reaction, theirs->reaction);
      EXPECT_LE(gap, impulse_tol) << name << " scene " << k << " mu " << mu;
      EXPECT_LE(distance(u_ours, p.velocity(theirs->reaction)), s.delassus.max * impulse_tol) << name << " scene " << k;
      worst_gap = std::max(worst_gap, gap / s.impulse);
    }

    // The faster variants stop on other iterates (conjugate acceleration's last step adds a
    // push; cycles skip quiet contacts until their last, full sweep): each residual is held to
    // the plain iteration's bound, and the uniqueness bound then holds as above with it.
    for (std::size_t v = 0; v < std::size(faster_sweeps); v++) {
      const CoreRun faster = run_core(scene, gauss_seidel_tolerance, max_sweeps, faster_sweeps[v]);
      ASSERT_TRUE(faster.report.converged) << faster_sweeps[v].name << ", scene " << k;
      const double r_faster = core_error(p, faster.reaction);
      EXPECT_LE(r_faster, core_residual_bound(s, mu)) << faster_sweeps[v].name << ", scene " << k;
      const double rounding = 1e3 * eps * (1.0 + mu) * (s.impulse + s.velocity);
      EXPECT_LE(distance(ours.reaction, faster.reaction), amplification * (r_ours + r_faster + 2.0 * rounding))
          << faster_sweeps[v].name << ", scene " << k << " mu " << mu;
      variant_updates[v] += faster.report.contact_updates;
    }
    plain_updates += ours.report.contact_updates;
  }
  // Lemke's failures are Siconos's; on these well-posed problems they stay rare.
  EXPECT_LE(lemke_rejected, scenes / 4);
  std::printf("unique scenes: %d, Lemke rejected %d, worst impulse gap / P %.2g; local solves plain %.0f", scenes,
              lemke_rejected, worst_gap, plain_updates);
  for (std::size_t v = 0; v < std::size(faster_sweeps); v++)
    std::printf(", %s %.0f", faster_sweeps[v].name, variant_updates[v]);
  std::printf("\n");
}

// Hyperstatic piles (nests close loops: mostly 2m > 3N, W singular) with large friction: the
// impulses need not be unique, so the core is held to the Coulomb law by both measures, and to
// Siconos's NSGS by running the same iteration: both start from zero impulses, sweep the
// contacts in the same order and solve each local problem exactly (unique for disks, W_ii
// diagonal), so after the same number of sweeps they differ only by rounding. That holds also
// when neither converges within the cap.
TEST(SiconosScene, HyperstaticPilesFollowTheSameIterationAsSiconosNsgs)
{
  std::mt19937_64 rng(7654321);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double mus[] = {0.05, 0.5, 2.0};
  const int scenes_per_mu = 5;
  int converged = 0, lemke_accepted_count = 0, lemke_same = 0;
  int variant_converged[std::size(faster_sweeps)] = {};
  for (double mu : mus) {
    for (int k = 0; k < scenes_per_mu; ++k) {
      const int disk_count = 5 + static_cast<int>(36 * unit(rng));
      Scene scene = random_scene(disk_count, 0.5, mu, rng);
      const std::vector<double> h = contact_jacobian(scene);
      const Fc2dProblem p = assemble(scene, h, mu);

      const CoreRun ours = run_core(scene, gauss_seidel_tolerance, max_sweeps);
      const SceneScales s = scene_scales(p, ours.reaction);
      check_assembly(scene, h, p, ours, s, rng);
      if (ours.report.converged) {
        ++converged;
        EXPECT_LE(core_error(p, ours.reaction), core_residual_bound(s, mu)) << "mu " << mu << " scene " << k;
        expect_same_measure(p, ours.reaction, s, mu, "core solution");
      }
      // The faster variants: other iterations, held to the same law and the same bound.
      for (std::size_t v = 0; v < std::size(faster_sweeps); v++) {
        const CoreRun faster = run_core(scene, gauss_seidel_tolerance, max_sweeps, faster_sweeps[v]);
        if (!faster.report.converged) continue;
        ++variant_converged[v];
        EXPECT_LE(core_error(p, faster.reaction), core_residual_bound(s, mu))
            << faster_sweeps[v].name << ", mu " << mu << " scene " << k;
      }

      const SiconosSolution nsgs = solve_with_siconos(p, SICONOS_FRICTION_2D_NSGS, gauss_seidel_tolerance, max_sweeps);
      if (nsgs.info == 0) {
        EXPECT_LE(core_error(p, nsgs.reaction), nsgs_residual_bound(s, p, mu)) << "mu " << mu << " scene " << k;
        expect_same_measure(p, nsgs.reaction, s, mu, "NSGS solution");
      }

      // Sweep for sweep. One sweep rounds each impulse by a few eps of the impulse scale
      // (a local solve and one velocity update per contact: 64 eps with room); without
      // cancellation the rounding accumulates at most linearly over the sweeps.
      const CoreRun same_sweeps = run_core(scene, 0.0, nsgs.iterations);
      // Fewer only if an exact fixed point stopped the core early: further sweeps would not move it.
      EXPECT_LE(same_sweeps.report.iterations, nsgs.iterations);
      const double sweep_tol = nsgs.iterations * 64.0 * eps * (s.impulse + s.velocity / s.delassus.max);
      EXPECT_LE(distance(same_sweeps.reaction, nsgs.reaction), sweep_tol)
          << "mu " << mu << " scene " << k << " after " << nsgs.iterations << " sweeps";
      EXPECT_LE(distance(p.velocity(same_sweeps.reaction), p.velocity(nsgs.reaction)), s.delassus.max * sweep_tol);

      // Lemke, when it succeeds, is another solution of the same law; it may be another one.
      const SiconosSolution lemke =
          solve_with_siconos(p, SICONOS_FRICTION_2D_LEMKE, gauss_seidel_tolerance, 100 * p.size());
      expect_same_measure(p, lemke.reaction, s, mu, "Lemke solution");
      if (lemke_accepted(p, lemke.reaction)) {
        ++lemke_accepted_count;
        lemke_same += distance(lemke.reaction, ours.reaction) <= 1e-8 * s.impulse;
      }
    }
  }
  EXPECT_GE(converged, 10);
  for (std::size_t v = 0; v < std::size(faster_sweeps); v++)
    EXPECT_GE(variant_converged[v], converged) << faster_sweeps[v].name;
  std::printf("hyperstatic scenes: %d, core converged %d (", 3 * scenes_per_mu, converged);
  for (std::size_t v = 0; v < std::size(faster_sweeps); v++)
    std::printf("%s%s %d", v ? ", " : "", faster_sweeps[v].name, variant_converged[v]);
  std::printf("); Lemke accepted %d, of which %d equal to the core's impulses within 1e-8 P\n", lemke_accepted_count,
              lemke_same);
}

}  // namespace
