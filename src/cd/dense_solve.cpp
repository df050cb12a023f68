// The states' dense solve (cd/dense_solve.h).
#include "cd/dense_solve.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace cd {

bool solve_dense(std::vector<double>& A, std::vector<double>& B, std::size_t k, std::size_t r)
{
  double largest = 0.0;
  for (const double a : A) largest = std::max(largest, std::fabs(a));
  const double singular = 1e-13 * largest;
  for (std::size_t col = 0; col < k; col++) {
    std::size_t pivot = col;
    for (std::size_t row = col + 1; row < k; row++)
      if (std::fabs(A[row * k + col]) > std::fabs(A[pivot * k + col])) pivot = row;
    if (!(std::fabs(A[pivot * k + col]) > singular)) return false;
    if (pivot != col) {
      for (std::size_t c = 0; c < k; c++) std::swap(A[pivot * k + c], A[col * k + c]);
      for (std::size_t c = 0; c < r; c++) std::swap(B[pivot * r + c], B[col * r + c]);
    }
    const double* top = &A[col * k];
    for (std::size_t row = col + 1; row < k; row++) {
      double* below = &A[row * k];
      const double factor = below[col] / top[col];
      if (factor == 0.0) continue;
      for (std::size_t c = col + 1; c < k; c++) below[c] -= factor * top[c];
      for (std::size_t c = 0; c < r; c++) B[row * r + c] -= factor * B[col * r + c];
    }
  }
  for (std::size_t col = k; col-- > 0;)
    for (std::size_t c = 0; c < r; c++) {
      double sum = B[col * r + c];
      for (std::size_t j = col + 1; j < k; j++) sum -= A[col * k + j] * B[j * r + c];
      B[col * r + c] = sum / A[col * k + col];
    }
  return true;
}

}  // namespace cd
