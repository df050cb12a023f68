// The dense solve of the contacts' states (cd/friction_states.h): their closed contacts' impulses
// from a linear system. Hand-written LU with partial pivoting that skips the rows a column does not
// reach: a block's system is as sparse as its contact network, and on the trapped chute step's
// blocks (146 to 400 unknowns) this ran 1.8 to 4.6 times faster than Eigen's PartialPivLU
// (bench/bench_dense_solve.cpp, doc/benchmarks.md).
#pragma once

#include <cstddef>
#include <vector>

namespace cd {

// Solves A X = B (A k x k, B k x r, row-major; A overwritten, X in B) by LU with partial
// pivoting; false if a pivot falls below 1e-13 of A's largest entry.
bool solve_dense(std::vector<double>& A, std::vector<double>& B, std::size_t k, std::size_t r = 1);

}  // namespace cd
