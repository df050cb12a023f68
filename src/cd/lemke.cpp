// Lemke's method in a dense tableau (cd/lemke.h).
#include "cd/lemke.h"

#include <cmath>
#include <cstddef>

namespace cd {

namespace {

// The tableau of w - M z - 1 z0 = q over the variables w (0..n-1), z (n..2n-1) and z0 (2n), each
// row naming its basic variable. Only the nonbasic variables' columns are stored, each in a slot
// of its own, with the right-hand side in the last: a basic variable's column is zero but in its
// row, where it holds that variable's pivot (about 1). A pivot so updates n + 2 columns rather
// than 2n + 2, each entry by the same operations as in the whole tableau; the leaving variable's
// column takes the entering one's slot. `cells` holds the slots, reused from solve to solve.
class Tableau {
 public:
  Tableau(const std::vector<double>& M, const std::vector<double>& q, std::vector<double>& cells)
      : n_(q.size()), cells_(cells), basis_(n_), slot_(2 * n_ + 1, none), diagonal_(2 * n_ + 1, 1.0)
  {
    cells_.resize(n_ * width());
    for (std::size_t i = 0; i < n_; i++) {
      for (std::size_t j = 0; j < n_; j++) at(i, j) = -M[i * n_ + j];
      at(i, n_) = -1.0;
      at(i, rhs()) = q[i];
      basis_[i] = i;
    }
    for (std::size_t k = n_; k <= artificial(); k++) slot_[k] = k - n_;
  }

  std::size_t size() const { return n_; }
  std::size_t artificial() const { return 2 * n_; }
  std::size_t basic(std::size_t row) const { return basis_[row]; }
  double value(std::size_t row) const { return at(row, rhs()); }
  // The complement of variable k: w_i <-> z_i.
  std::size_t complement(std::size_t k) const { return k < n_ ? k + n_ : k - n_; }

  void pivot(std::size_t row, std::size_t column)
  {
    const std::size_t slot = slot_[column], leaving = basis_[row];
    double* pivot_row = &cells_[row * width()];
    const double scale = 1.0 / pivot_row[slot];
    for (std::size_t j = 0; j < width(); j++) pivot_row[j] *= scale;
    diagonal_[column] = pivot_row[slot];
    pivot_row[slot] = diagonal_[leaving] * scale;
    for (std::size_t i = 0; i < n_; i++) {
      if (i == row) continue;
      double* other = &cells_[i * width()];
      const double factor = other[slot];
      if (factor == 0.0) continue;
      other[slot] = 0.0;  // the leaving column's entry before the pivot
      for (std::size_t j = 0; j < width(); j++) other[j] -= factor * pivot_row[j];
    }
    basis_[row] = column;
    slot_[leaving] = slot;
    slot_[column] = none;
  }

  // The row that leaves when `column` enters: the lexicographic minimum of (value, basis
  // inverse row) / entry over the rows whose entry is positive; the artificial variable wins
  // a tie. n_ (none) on a ray.
  std::size_t leaving_row(std::size_t column) const
  {
    const std::size_t slot = slot_[column];
    double largest = 0.0;
    for (std::size_t i = 0; i < n_; i++) largest = std::fmax(largest, std::fabs(at(i, slot)));
    const double floor = 1e-12 * largest;
    std::size_t best = n_;
    for (std::size_t i = 0; i < n_; i++) {
      if (!(at(i, slot) > floor)) continue;
      if (best == n_ || precedes(i, best, slot)) best = i;
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
  static constexpr std::size_t none = static_cast<std::size_t>(-1);

  std::size_t width() const { return n_ + 2; }
  std::size_t rhs() const { return n_ + 1; }
  double& at(std::size_t i, std::size_t slot) { return cells_[i * width() + slot]; }
  double at(std::size_t i, std::size_t slot) const { return cells_[i * width() + slot]; }
  // Row i's entry in variable k's column, stored or not.
  double entry(std::size_t i, std::size_t k) const
  {
    if (slot_[k] != none) return at(i, slot_[k]);
    return basis_[i] == k ? diagonal_[k] : 0.0;
  }

  bool precedes(std::size_t a, std::size_t b, std::size_t slot) const
  {
    const double ratio_a = value(a) / at(a, slot), ratio_b = value(b) / at(b, slot);
    const double tie = 1e-12 * std::fmax(1.0, std::fmax(std::fabs(ratio_a), std::fabs(ratio_b)));
    if (ratio_a < ratio_b - tie) return true;
    if (ratio_a > ratio_b + tie) return false;
    if (basis_[a] == artificial()) return true;
    if (basis_[b] == artificial()) return false;
    for (std::size_t j = 0; j < n_; j++) {
      const double lex_a = entry(a, j) / at(a, slot), lex_b = entry(b, j) / at(b, slot);
      if (lex_a != lex_b) return lex_a < lex_b;
    }
    return a < b;
  }

  std::size_t n_;
  std::vector<double>& cells_;
  std::vector<std::size_t> basis_;
  std::vector<std::size_t> slot_;  // per variable: its slot, none while basic
  std::vector<double> diagonal_;   // per variable: its pivot while basic
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
  thread_local std::vector<double> cells;
  Tableau tableau(M, q, cells);
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
