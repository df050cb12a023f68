// Lemke's method in a dense tableau (cd/lemke.h).
#include "cd/lemke.h"

#include <cmath>
#include <cstddef>

namespace cd {

namespace {

// The tableau of w - M z - 1 z0 = q: columns w (0..n-1, they hold the basis inverse), z
// (n..2n-1), z0 (2n) and the right-hand side (2n+1); each row names its basic variable.
class Tableau {
 public:
  Tableau(const std::vector<double>& M, const std::vector<double>& q) : n_(q.size()), cells_(n_ * width()), basis_(n_)
  {
    for (std::size_t i = 0; i < n_; i++) {
      at(i, i) = 1.0;
      for (std::size_t j = 0; j < n_; j++) at(i, n_ + j) = -M[i * n_ + j];
      at(i, artificial()) = -1.0;
      at(i, rhs()) = q[i];
      basis_[i] = i;
    }
  }

  std::size_t size() const { return n_; }
  std::size_t artificial() const { return 2 * n_; }
  std::size_t basic(std::size_t row) const { return basis_[row]; }
  double value(std::size_t row) const { return at(row, rhs()); }
  // The complement of variable k: w_i <-> z_i.
  std::size_t complement(std::size_t k) const { return k < n_ ? k + n_ : k - n_; }

  void pivot(std::size_t row, std::size_t column)
  {
    double* pivot_row = &cells_[row * width()];
    const double scale = 1.0 / pivot_row[column];
    for (std::size_t j = 0; j < width(); j++) pivot_row[j] *= scale;
    for (std::size_t i = 0; i < n_; i++) {
      if (i == row) continue;
      double* other = &cells_[i * width()];
      const double factor = other[column];
      if (factor == 0.0) continue;
      for (std::size_t j = 0; j < width(); j++) other[j] -= factor * pivot_row[j];
      other[column] = 0.0;
    }
    basis_[row] = column;
  }

  // The row that leaves when `column` enters: the lexicographic minimum of (value, basis
  // inverse row) / entry over the rows whose entry is positive; the artificial variable wins
  // a tie. n_ (none) on a ray.
  std::size_t leaving_row(std::size_t column) const
  {
    double largest = 0.0;
    for (std::size_t i = 0; i < n_; i++) largest = std::fmax(largest, std::fabs(at(i, column)));
    const double floor = 1e-12 * largest;
    std::size_t best = n_;
    for (std::size_t i = 0; i < n_; i++) {
      if (!(at(i, column) > floor)) continue;
      if (best == n_ || precedes(i, best, column)) best = i;
    }
    return best;
  }

  // The first pivot: z0 enters where q is most negative (after it every value is >= 0).
  std::size_t most_negative_row() const
  {
    std::size_t best = 0;
    for (std::size_t i = 1; i < n_; i++)
      if (value(i) < value(best)) best = i;
    return best;
  }

 private:
  std::size_t width() const { return 2 * n_ + 2; }
  std::size_t rhs() const { return 2 * n_ + 1; }
  double& at(std::size_t i, std::size_t j) { return cells_[i * width() + j]; }
  double at(std::size_t i, std::size_t j) const { return cells_[i * width() + j]; }

  bool precedes(std::size_t a, std::size_t b, std::size_t column) const
  {
    const double ratio_a = value(a) / at(a, column), ratio_b = value(b) / at(b, column);
    const double tie = 1e-12 * std::fmax(1.0, std::fmax(std::fabs(ratio_a), std::fabs(ratio_b)));
    if (ratio_a < ratio_b - tie) return true;
    if (ratio_a > ratio_b + tie) return false;
    if (basis_[a] == artificial()) return true;
    if (basis_[b] == artificial()) return false;
    for (std::size_t j = 0; j < n_; j++) {
      const double lex_a = at(a, j) / at(a, column), lex_b = at(b, j) / at(b, column);
      if (lex_a != lex_b) return lex_a < lex_b;
    }
    return a < b;
  }

  std::size_t n_;
  std::vector<double> cells_;
  std::vector<std::size_t> basis_;
};

}  // namespace

LemkeResult solve_lcp_lemke(const std::vector<double>& M, const std::vector<double>& q, std::vector<double>& z,
                            int max_pivots)
{
  const std::size_t n = q.size();
  z.assign(n, 0.0);
  LemkeResult result;
  bool feasible_at_zero = true;
  for (const double qi : q) feasible_at_zero = feasible_at_zero && qi >= 0.0;
  if (feasible_at_zero) {
    result.solved = true;
    return result;
  }
  Tableau tableau(M, q);
  std::size_t row = tableau.most_negative_row();
  std::size_t entering = tableau.artificial();
  while (result.pivots < max_pivots) {
    const std::size_t leaving = tableau.basic(row);
    tableau.pivot(row, entering);
    ++result.pivots;
    if (leaving == tableau.artificial()) {
      for (std::size_t i = 0; i < n; i++)
        if (tableau.basic(i) >= n && tableau.basic(i) < 2 * n) z[tableau.basic(i) - n] = tableau.value(i);
      result.solved = true;
      return result;
    }
    entering = tableau.complement(leaving);
    row = tableau.leaving_row(entering);
    if (row == n) return result;  // a ray
  }
  return result;
}

}  // namespace cd
