// Siconos numerics' solvers behind one call (bench/peers/siconos_solvers.h).
#include "siconos_solvers.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

// fc2d_compute_error.h declares C99 `restrict` parameters.
#define restrict __restrict__
#include "CSparseMatrix.h"
#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "NumericsSparseMatrix.h"
#include "SparseBlockMatrix.h"
#include "fc2d_compute_error.h"
#undef restrict
#include "siconos_variants.h"

namespace peers {

namespace {

struct Method {
  std::string name;
  int id;
  bool planar;  // fc2d (else the 3D embedding)
  bool dense;   // needs W dense
};

const std::vector<Method>& methods()
{
  static const std::vector<Method> all = {
      {"fc2d_nsgs", SICONOS_FRICTION_2D_NSGS, true, false},
      {"fc2d_cpg", SICONOS_FRICTION_2D_CPG, true, true},
      {"fc2d_lemke", SICONOS_FRICTION_2D_LEMKE, true, true},
      {"fc2d_enum", SICONOS_FRICTION_2D_ENUM, true, true},
      {"fc3d_nsgs", SICONOS_FRICTION_3D_NSGS, false, false},
      {"fc3d_nsgsv", SICONOS_FRICTION_3D_NSGSV, false, true},
      {"fc3d_prox", SICONOS_FRICTION_3D_PROX, false, false},
      {"fc3d_tfp", SICONOS_FRICTION_3D_TFP, false, false},
      {"fc3d_dsfp", SICONOS_FRICTION_3D_DSFP, false, false},
      {"fc3d_pfp", SICONOS_FRICTION_3D_PFP, false, false},
      {"fc3d_fpp", SICONOS_FRICTION_3D_FPP, false, false},
      {"fc3d_eg", SICONOS_FRICTION_3D_EG, false, false},
      {"fc3d_vi_fpp", SICONOS_FRICTION_3D_VI_FPP, false, false},
      {"fc3d_vi_eg", SICONOS_FRICTION_3D_VI_EG, false, false},
      {"fc3d_hp", SICONOS_FRICTION_3D_HP, false, false},
      {"fc3d_nsn_ac", SICONOS_FRICTION_3D_NSN_AC, false, false},
      {"fc3d_nsn_fb", SICONOS_FRICTION_3D_NSN_FB, false, false},
      {"fc3d_nsn_nm", SICONOS_FRICTION_3D_NSN_NM, false, false},
      {"fc3d_admm", SICONOS_FRICTION_3D_ADMM, false, false},
      {"fc3d_aclmfp", SICONOS_FRICTION_3D_ACLMFP, false, false},
      {"fc3d_soclcp", SICONOS_FRICTION_3D_SOCLCP, false, false},
      {"fc3d_glocker_fixed_point", SICONOS_FRICTION_3D_NCPGlockerFBFixedPoint, false, true},
  };
  return all;
}

// The solver of a name or of a variant's name ("fc3d_nsn_fb[ls=armijo]").
const Method& method(const std::string& name)
{
  const std::string solver = parse_variant(name).solver;
  for (const Method& m : methods())
    if (m.name == solver) return m;
  throw std::invalid_argument("siconos_solvers: no solver '" + solver + "'");
}

// A Siconos matrix from triplets (row, column, value), dense or by blocks of `block` rows.
NumericsMatrix* siconos_matrix(int size, int block, bool dense, const std::vector<long>& rows,
                               const std::vector<long>& cols, const std::vector<double>& values)
{
  if (dense) {
    NumericsMatrix* m = NM_create(NM_DENSE, size, size);
    std::fill(m->matrix0, m->matrix0 + static_cast<std::size_t>(size) * size, 0.0);
    for (std::size_t e = 0; e < values.size(); e++) m->matrix0[rows[e] + cols[e] * size] += values[e];
    return m;
  }
  NumericsMatrix* triplet = NM_create(NM_SPARSE, size, size);
  NM_triplet_alloc(triplet, static_cast<CS_INT>(values.size()));
  triplet->matrix2->origin = NSM_TRIPLET;
  for (std::size_t e = 0; e < values.size(); e++) CSparseMatrix_entry(NM_triplet(triplet), rows[e], cols[e], values[e]);
  NumericsMatrix* m = NM_create(NM_SPARSE_BLOCK, size, size);
  SBM_from_csparse(block, NM_csc(triplet), m->matrix1);
  NM_free(triplet);
  return m;
}

// The problem as Siconos holds it, in dimension 2 or embedded in 3.
class SiconosProblem {
 public:
  SiconosProblem(const LocalProblem& p, int dimension, bool dense) : mu_(p.mu), q_(dimension * p.contacts, 0.0)
  {
    std::vector<long> rows, cols;
    std::vector<double> values;
    const auto at = [&](int i) { return static_cast<long>(i / 2 * dimension + i % 2); };
    for (int j = 0; j < p.size(); j++)
      for (int e = p.column_start[j]; e < p.column_start[j + 1]; e++) {
        rows.push_back(at(p.row[e]));
        cols.push_back(at(j));
        values.push_back(p.value[e]);
        if (dimension == 3 && p.row[e] == j && j % 2 == 1) {  // the second tangent's diagonal: W_tt
          rows.push_back(at(j) + 1);
          cols.push_back(at(j) + 1);
          values.push_back(p.value[e]);
        }
      }
    for (int i = 0; i < p.size(); i++) q_[at(i)] = p.q[i];
    problem_.dimension = dimension;
    problem_.numberOfContacts = p.contacts;
    problem_.M = siconos_matrix(dimension * p.contacts, dimension, dense, rows, cols, values);
    problem_.q = q_.data();
    problem_.mu = mu_.data();
  }
  ~SiconosProblem() { NM_free(problem_.M); }
  SiconosProblem(const SiconosProblem&) = delete;
  SiconosProblem& operator=(const SiconosProblem&) = delete;
  FrictionContactProblem* get() { return &problem_; }

 private:
  std::vector<double> mu_;
  std::vector<double> q_;
  FrictionContactProblem problem_{};
};

std::vector<double> embedded(const std::vector<double>& r2)
{
  std::vector<double> r3(r2.size() / 2 * 3, 0.0);
  for (std::size_t i = 0; i < r2.size(); i++) r3[i / 2 * 3 + i % 2] = r2[i];
  return r3;
}

std::vector<double> planar(const std::vector<double>& r3)
{
  std::vector<double> r2(r3.size() / 3 * 2);
  for (std::size_t i = 0; i < r2.size(); i++) r2[i] = r3[i / 2 * 3 + i % 2];
  return r2;
}

double norm(const std::vector<double>& x)
{
  double sum = 0.0;
  for (const double v : x) sum += v * v;
  return std::sqrt(sum);
}

}  // namespace

double cpu_seconds()
{
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

const std::vector<std::string>& siconos_solver_names()
{
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const Method& m : methods()) all.push_back(m.name);
    return all;
  }();
  return names;
}

OptionsPointer siconos_options(const std::string& solver)
{
  OptionsPointer options(solver_options_create(method(solver).id), solver_options_delete);
  apply_variant(parse_variant(solver), *options);
  return options;
}

SiconosResult solve_with_siconos(const LocalProblem& problem, const std::string& solver,
                                 const SiconosSettings& settings, const std::vector<double>& start)
{
  const Method& m = method(solver);
  if (m.dense && (m.planar ? 2 : 3) * problem.contacts > settings.dense_rows_limit)
    throw std::invalid_argument("siconos_solvers: " + solver + " takes W dense: " + std::to_string(problem.contacts) +
                                " contacts is over the limit");
  SiconosProblem siconos(problem, m.planar ? 2 : 3, m.dense);
  OptionsPointer options = siconos_options(solver);
  options->dparam[SICONOS_DPARAM_TOL] = settings.tolerance;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = settings.max_iterations;
  std::vector<double> reaction = m.planar ? start : embedded(start);
  std::vector<double> velocity(reaction.size(), 0.0);
  SiconosResult result;
  const double begin = cpu_seconds();
  result.info = m.planar ? fc2d_driver(siconos.get(), reaction.data(), velocity.data(), options.get())
                         : fc3d_driver(siconos.get(), reaction.data(), velocity.data(), options.get());
  result.seconds = cpu_seconds() - begin;
  result.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  result.reaction = m.planar ? reaction : planar(reaction);
  result.error = error(problem, result.reaction);
  return result;
}

struct ErrorMeter::Held {
  explicit Held(const LocalProblem& p) : problem(p, 2, false), q_norm(norm(p.q)), velocity(p.size()) {}
  SiconosProblem problem;
  double q_norm;
  std::vector<double> reaction, velocity;
};

ErrorMeter::ErrorMeter(const LocalProblem& problem) : held_(std::make_unique<Held>(problem)) {}
ErrorMeter::~ErrorMeter() = default;

double ErrorMeter::operator()(const std::vector<double>& reaction)
{
  held_->reaction = reaction;  // fc2d_compute_error's z is not const
  double value = 0.0;
  fc2d_compute_error(held_->problem.get(), held_->reaction.data(), held_->velocity.data(), 0.0, held_->q_norm, &value);
  return value;
}

double error(const LocalProblem& problem, const std::vector<double>& reaction)
{
  return ErrorMeter(problem)(reaction);
}

double error_at_problem_scale(const LocalProblem& problem, const std::vector<double>& reaction)
{
  const auto scale = [&](const std::vector<double>& r) {
    return std::max({norm(r), norm(problem.velocity(r)), norm(problem.q)});
  };
  return error(problem, reaction) * scale(reaction) / scale(problem.warm_start);
}

}  // namespace peers
