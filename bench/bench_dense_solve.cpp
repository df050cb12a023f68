// The dense solve of the contacts' states (cd/friction_states.cpp) measured on the systems it
// meets: the block of a trapped chute step (tests/data/trapped_mu2_28deg.cdp, mu 2, 4 601
// contacts, 300 of the deck's sweeps at 1e-4), the contacts around its residual's carriers 1 to 3
// shared grains out, every contact closed and sticking, unknowns (p_n, p_t) contact by contact as
// the states' solve numbers them. The core's hand-written elimination (cd::solve_dense) against
// Eigen's partial-pivoting LU, with one right-hand side (the states' solve) and 17 (the cycling
// contacts' solve of 8 contacts).
//
//   bench_dense_solve [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <vector>

#include "cd/block_solve.h"
#include "cd/dense_solve.h"
#include "cd/gauss_seidel.h"
#include "cd/problem_file.h"

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Eigen's partial-pivoting LU, the same singularity test on its pivots.
bool solve_by_eigen(std::vector<double>& A, std::vector<double>& B, std::size_t k, std::size_t r)
{
  const Eigen::Map<const RowMatrix> a(A.data(), static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  Eigen::Map<RowMatrix> b(B.data(), static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(r));
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
  const double singular = 1e-13 * a.cwiseAbs().maxCoeff();
  if (!(lu.matrixLU().diagonal().cwiseAbs().minCoeff() > singular)) return false;
  b = lu.solve(b);
  return true;
}

// The states' system of the trapped block `hops` grains around its carriers: every contact
// closed and sticking, A (2m x 2m) and its right-hand side -u0, unknowns p_n, p_t of each contact.
struct System {
  std::vector<double> A, b;
  std::size_t k = 0;
};

System trapped_system(int hops)
{
  const cd::ContactProblem saved = cd::read_problem(CD_TEST_DATA "/trapped_mu2_28deg.cdp");
  std::vector<cd::Contact> contacts = saved.contacts;
  std::vector<cd::BodyVelocity> velocity = saved.free_velocity;
  cd::apply_impulses(contacts, velocity);
  cd::SolverSettings sweeps;
  sweeps.tolerance = 1e-4;
  sweeps.max_iterations = 300;
  sweeps.gauss_seidel.acceleration = cd::Acceleration::conjugate;
  sweeps.gauss_seidel.stall_window = 0;
  cd::solve_gauss_seidel(contacts, velocity, sweeps);
  const std::vector<int> seeds = cd::residual_carriers(contacts, velocity, 0.9, 16);
  const std::vector<int> block = cd::block_around(contacts, static_cast<int>(velocity.size()), seeds, hops, 200);
  const cd::BlockProblem problem = cd::block_problem(contacts, velocity, block);
  const std::size_t m = problem.size();
  System system;
  system.k = 2 * m;
  system.A.assign(system.k * system.k, 0.0);
  system.b.resize(system.k);
  for (std::size_t i = 0; i < m; i++) {
    system.b[2 * i] = -problem.u0[i], system.b[2 * i + 1] = -problem.u0[m + i];
    for (std::size_t j = 0; j < m; j++) {
      system.A[2 * i * system.k + 2 * j] = problem.nn(i, j), system.A[2 * i * system.k + 2 * j + 1] = problem.nt(i, j);
      system.A[(2 * i + 1) * system.k + 2 * j] = problem.tn(i, j);
      system.A[(2 * i + 1) * system.k + 2 * j + 1] = problem.tt(i, j);
    }
  }
  return system;
}

// Solves the block's system with `columns` right-hand sides (1: the states' solve; 1 + 2c: the
// cycling contacts' solve of c contacts) by `solve`.
template <bool (*solve)(std::vector<double>&, std::vector<double>&, std::size_t, std::size_t)>
void BM_DenseSolve(benchmark::State& state)
{
  const System system = trapped_system(static_cast<int>(state.range(0)));
  const std::size_t columns = static_cast<std::size_t>(state.range(1));
  std::vector<double> rhs(system.k * columns);
  for (std::size_t row = 0; row < system.k; row++)
    for (std::size_t c = 0; c < columns; c++) rhs[row * columns + c] = system.b[row] * (1.0 + 0.1 * c);
  for (auto _ : state) {
    std::vector<double> A = system.A, B = rhs;
    if (!solve(A, B, system.k, columns)) state.SkipWithError("singular");
    benchmark::DoNotOptimize(B.data());
  }
  state.counters["unknowns"] = static_cast<double>(system.k);
}

void sizes(benchmark::internal::Benchmark* b)
{
  for (const int hops : {1, 2, 3})
    for (const int columns : {1, 17}) b->Args({hops, columns});
}

// The core's: cd::solve_dense.
bool solve_by_hand(std::vector<double>& A, std::vector<double>& B, std::size_t k, std::size_t r)
{
  return cd::solve_dense(A, B, k, r);
}

BENCHMARK(BM_DenseSolve<solve_by_hand>)->Name("hand_written")->Apply(sizes);
BENCHMARK(BM_DenseSolve<solve_by_eigen>)->Name("eigen")->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
