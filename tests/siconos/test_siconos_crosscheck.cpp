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

// ---------------------------------------------------------------------------------------------
// Many contacts: Gauss–Seidel on a disk cluster against fc2d solvers on the assembled problem
// ---------------------------------------------------------------------------------------------

// A contact as the test derives it from the disks alone.
struct ContactKinematics {
  int body_a = 0;
  int body_b = 0;        // cd::world_body for a wall
  double nx = 0.0;       // unit normal from b to a
  double ny = 0.0;
  double lever_a = 0.0;  // centre-to-contact distances (m); 0 for the world
  double lever_b = 0.0;
};

struct Scene {
  std::vector<cd::Disk> disks;  // indexed by body; disks[0] stands for the world
  std::vector<ContactKinematics> kinematics;
  std::vector<cd::Contact> contacts;
  cd::BodySet bodies;
  int body_count() const { return static_cast<int>(disks.size()) - 1; }  // the world excluded
};

// Disks of radius U[0.4, 0.6] dropped one by one against the cluster, each overlapping one
// placed disk, or two (a nest, closing loops of contacts), by 1e-6..1e-3 m and no other disk by
// more: every intended contact has gap < 0, an impact, so zero restitution leaves no velocity
// bias and q is the free relative velocity.
std::vector<cd::Disk> random_cluster(int count, std::mt19937_64& rng)
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
    if (placed > 1 && unit(rng) < 0.5) {
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

// The cluster on a floor and against a left wall (both overlapping their nearest disks by
// 5e-4 m), bodies with m = pi r^2, I = m r^2 / 2 and a free velocity that compresses the
// cluster towards its centre and the floor, plus noise and spin.
Scene random_scene(int disk_count, double mu, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Scene s;
  s.disks = random_cluster(disk_count, rng);
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
  const cd::StepParameters step{1e-3, 0.5};
  auto add = [&](const cd::ContactGeometry& g, const ContactKinematics& k) {
    cd::Contact c = cd::contact_frame(g);
    cd::prepare_mechanics(c, law, s.bodies, step);
    s.contacts.push_back(c);
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
      add(cd::disk_world_geometry(i, d, 0.0, d.y - floor_y, 0.0, 1.0),
          {i, cd::world_body, 0.0, 1.0, d.radius, 0.0});
    if (d.x - d.radius < wall_x)
      add(cd::disk_world_geometry(i, d, d.x - wall_x, 0.0, 1.0, 0.0),
          {i, cd::world_body, 1.0, 0.0, d.radius, 0.0});
  }
  return s;
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

TEST(SiconosScene, GaussSeidelAgreesWithFc2dSolvers)
{
  std::mt19937_64 rng(1234567);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double mus[] = {0.0, 0.05, 0.5, 2.0};
  const int scenes_per_mu = 6;

  for (double mu : mus) {
    for (int k = 0; k < scenes_per_mu; ++k) {
      const int disk_count = 5 + static_cast<int>(36 * unit(rng));
      Scene scene = random_scene(disk_count, mu, rng);
      const int m = static_cast<int>(scene.contacts.size());
      const std::vector<double> h = contact_jacobian(scene);
      const Fc2dProblem p = assemble(scene, h, mu);

      // The test's H against the core's kinematics, on an arbitrary velocity field.
      std::vector<cd::BodyVelocity> probe(scene.body_count() + 1);
      for (int i = 1; i <= scene.body_count(); ++i)
        probe[i] = {2.0 * unit(rng) - 1.0, 2.0 * unit(rng) - 1.0, 2.0 * unit(rng) - 1.0};
      const std::vector<double> u_probe = times(h, 2 * m, generalized(probe));
      for (int c = 0; c < m; ++c) {
        const cd::Contact& contact = scene.contacts[c];
        const cd::Local2 u = cd::relative_velocity(contact, probe[contact.body_a], probe[contact.body_b]);
        EXPECT_NEAR(u.n, u_probe[2 * c], 1e-14);
        EXPECT_NEAR(u.t, u_probe[2 * c + 1], 1e-14);
        EXPECT_NEAR(contact.delassus.nn, p.w(2 * c, 2 * c), 1e-14 * p.w(2 * c, 2 * c));
        EXPECT_NEAR(contact.delassus.nt, p.w(2 * c, 2 * c + 1), 1e-14 * p.w(2 * c, 2 * c));
        EXPECT_NEAR(contact.delassus.tt, p.w(2 * c + 1, 2 * c + 1), 1e-14 * p.w(2 * c + 1, 2 * c + 1));
      }

      // The core: Gauss–Seidel from zero impulses.
      std::vector<cd::BodyVelocity> velocity = scene.bodies.velocity;
      cd::apply_impulses(scene.contacts, velocity);
      cd::SolverSettings settings;
      settings.tolerance = 1e-12;
      settings.max_iterations = 200000;
      const cd::SolveReport report = cd::solve_gauss_seidel(scene.contacts, velocity, settings);
      EXPECT_TRUE(report.converged);
      std::vector<double> r_ours(2 * m), u_bodies(2 * m);
      for (int c = 0; c < m; ++c) {
        const cd::Contact& contact = scene.contacts[c];
        r_ours[2 * c] = contact.impulse.n;
        r_ours[2 * c + 1] = contact.impulse.t;
        const cd::Local2 u = cd::relative_velocity(contact, velocity[contact.body_a], velocity[contact.body_b]);
        u_bodies[2 * c] = u.n;
        u_bodies[2 * c + 1] = u.t;
      }
      const std::vector<double> u_ours = p.velocity(r_ours);

      const Spectrum spectrum = symmetric_spectrum(p.delassus, 2 * m);
      std::vector<double> tangential_gram(m * m, 0.0);  // W_T W_T^T, W_T the tangential rows
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
          for (int l = 0; l < 2 * m; ++l) tangential_gram[i + j * m] += p.w(2 * i + 1, l) * p.w(2 * j + 1, l);
      const double tangential_norm = std::sqrt(symmetric_spectrum(tangential_gram, m).max);
      const double monotonicity = spectrum.min - mu * tangential_norm;
      const double lipschitz = spectrum.max + mu * tangential_norm;

      const double impulse_scale = std::max(norm2(r_ours), norm2(p.free_velocity) / spectrum.max);
      const double velocity_scale = norm2(p.free_velocity) + spectrum.max * impulse_scale;

      const double ours_core = core_error(p, r_ours), ours_siconos = siconos_error(p, r_ours);
      std::printf("mu %g disks %d contacts %d: GS %d iterations, lambda [%.3g, %.3g], |W_T| %.3g, c %.3g; "
                  "u bodies-assembled %.3g; ours residual %.3g / %.3g (scale P %.3g V %.3g)\n",
                  mu, disk_count, m, report.iterations, spectrum.min, spectrum.max, tangential_norm,
                  monotonicity, distance(u_bodies, u_ours) / velocity_scale, ours_core / impulse_scale,
                  ours_siconos / impulse_scale, impulse_scale, velocity_scale);

      const SiconosSolution nsgs = solve_with_siconos(p, SICONOS_FRICTION_2D_NSGS, 1e-12, 200000);
      const SiconosSolution lemke = solve_with_siconos(p, SICONOS_FRICTION_2D_LEMKE, 1e-12, 100000);
      for (const auto* s : {&nsgs, &lemke}) {
        const double e_core = core_error(p, s->reaction), e_sic = siconos_error(p, s->reaction);
        std::printf("   %s: info %d iterations %d residual %.3g / %.3g, impulse gap %.3g, velocity gap %.3g\n",
                    s == &nsgs ? "NSGS" : "Lemke", s->info, s->iterations, e_core / impulse_scale,
                    e_sic / impulse_scale, distance(r_ours, s->reaction) / impulse_scale,
                    distance(u_ours, p.velocity(s->reaction)) / velocity_scale);
      }
      if (m <= 5) {
        const SiconosSolution en = solve_with_siconos(p, SICONOS_FRICTION_2D_ENUM, 1e-12, 100000);
        std::printf("   Enum: info %d residual %.3g, impulse gap %.3g\n", en.info,
                    core_error(p, en.reaction) / impulse_scale, distance(r_ours, en.reaction) / impulse_scale);
      }
    }
  }
}

}  // namespace
