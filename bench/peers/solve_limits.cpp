// What bounds a solve on a local problem (bench/peers/solve_limits.h).
#include "solve_limits.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace peers {

Mobility mobility(const std::vector<cd::Contact>& contacts, double impulse_scale)
{
  Mobility result;
  std::map<int, int> column_of;  // grain (body index) -> its first column
  const auto grain_column = [&](int body, double inv_mass) {
    if (body <= 0 || !(inv_mass > 0.0)) return -1;  // the world, or an immobile body
    const auto [at, added] = column_of.emplace(body, 3 * static_cast<int>(column_of.size()));
    return at->second;
  };
  std::vector<Eigen::Triplet<double>> entries;
  const double unscale = 1.0 / std::sqrt(impulse_scale);
  for (std::size_t k = 0; k < contacts.size(); k++) {
    const cd::Contact& c = contacts[k];
    const int n_row = 2 * static_cast<int>(k), t_row = n_row + 1;
    // Body a sees +H, body b -H in translation; a tangential impulse spins each disk by
    // -lever * inverse inertia (cd::apply_impulse), and relative_velocity reads -lever * spin.
    const struct {
      int body;
      double sign, inv_mass, lever, spin_gain;
    } sides[] = {{c.body_a, 1.0, c.inv_mass_a, c.lever_a, c.spin_gain_a},
                 {c.body_b, -1.0, c.inv_mass_b, c.lever_b, c.spin_gain_b}};
    for (const auto& side : sides) {
      const int column = grain_column(side.body, side.inv_mass);
      if (column < 0) continue;
      const double m = side.sign * std::sqrt(side.inv_mass) * unscale;
      entries.emplace_back(n_row, column, m * c.normal_x);
      entries.emplace_back(n_row, column + 1, m * c.normal_y);
      entries.emplace_back(t_row, column, -m * c.normal_y);
      entries.emplace_back(t_row, column + 1, m * c.normal_x);
      if (side.lever > 0.0 && side.spin_gain > 0.0) {
        const double inv_inertia = side.spin_gain / side.lever;
        entries.emplace_back(t_row, column + 2, -side.lever * std::sqrt(inv_inertia) * unscale);
      }
    }
  }
  result.grains = static_cast<int>(column_of.size());
  result.factor.resize(2 * static_cast<int>(contacts.size()), 3 * result.grains);
  result.factor.setFromTriplets(entries.begin(), entries.end());
  return result;
}

double factor_mismatch(const Mobility& mobility, const LocalProblem& problem)
{
  SparseMatrix w(problem.size(), problem.size());
  std::vector<Eigen::Triplet<double>> entries;
  double largest = 0.0;
  for (int j = 0; j < problem.size(); j++)
    for (int e = problem.column_start[j]; e < problem.column_start[j + 1]; e++) {
      entries.emplace_back(problem.row[e], j, problem.value[e]);
      largest = std::max(largest, std::abs(problem.value[e]));
    }
  w.setFromTriplets(entries.begin(), entries.end());
  const SparseMatrix product = mobility.factor * SparseMatrix(mobility.factor.transpose());
  const SparseMatrix difference = product - w;
  double worst = 0.0;
  for (int j = 0; j < difference.outerSize(); j++)
    for (SparseMatrix::InnerIterator it(difference, j); it; ++it) worst = std::max(worst, std::abs(it.value()));
  return largest > 0.0 ? worst / largest : worst;
}

int sparse_rank(const SparseMatrix& c)
{
  if (c.rows() == 0 || c.cols() == 0) return 0;
  SparseMatrix tall = c.rows() >= c.cols() ? c : SparseMatrix(c.transpose());
  tall.makeCompressed();
  Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>> qr(tall);
  return static_cast<int>(qr.rank());
}

Spectrum gram_spectrum(const SparseMatrix& c, int dense_limit)
{
  Spectrum s;
  s.rows = static_cast<int>(c.rows());
  if (c.rows() == 0 || c.cols() == 0) {
    s.null_dimension = s.rows;
    return s;
  }
  if (std::min(c.rows(), c.cols()) > dense_limit) {
    s.rank = sparse_rank(c);
    s.null_dimension = s.rows - s.rank;
    s.largest = s.smallest_nonzero = s.largest_zero = NAN;
    return s;
  }
  const SparseMatrix ct = c.transpose();
  const Eigen::MatrixXd gram = c.rows() <= c.cols() ? Eigen::MatrixXd(c * ct) : Eigen::MatrixXd(ct * c);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(gram, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& values = solver.eigenvalues();  // ascending
  s.largest = values(values.size() - 1);
  const double cut = zero_threshold * s.largest;
  for (Eigen::Index i = 0; i < values.size(); i++) {
    if (values(i) > cut) {
      if (s.rank == 0) s.smallest_nonzero = values(i);
      s.rank++;
    } else {
      s.largest_zero = std::max(s.largest_zero, values(i));
    }
  }
  s.null_dimension = s.rows - s.rank;
  return s;
}

std::vector<State> contact_states(const LocalProblem& problem, const std::vector<double>& reaction, double tolerance)
{
  double largest_normal = 0.0;
  for (int i = 0; i < problem.contacts; i++) largest_normal = std::max(largest_normal, reaction[2 * i]);
  std::vector<State> states(problem.contacts, State::open);
  for (int i = 0; i < problem.contacts; i++) {
    const double rn = reaction[2 * i], rt = reaction[2 * i + 1];
    if (rn <= tolerance * largest_normal) continue;
    states[i] = std::abs(rt) >= problem.mu[i] * rn * (1.0 - tolerance) ? State::slide : State::stick;
  }
  return states;
}

SparseMatrix free_directions(const LocalProblem& problem, const std::vector<double>& reaction,
                             const std::vector<State>& states)
{
  std::vector<Eigen::Triplet<double>> entries;
  int column = 0;
  for (int i = 0; i < problem.contacts; i++) {
    if (states[i] == State::stick) {
      entries.emplace_back(2 * i, column++, 1.0);
      entries.emplace_back(2 * i + 1, column++, 1.0);
    } else if (states[i] == State::slide) {
      entries.emplace_back(2 * i, column, 1.0);
      entries.emplace_back(2 * i + 1, column++, reaction[2 * i + 1] / reaction[2 * i]);
    }
  }
  SparseMatrix p(problem.size(), column);
  p.setFromTriplets(entries.begin(), entries.end());
  return p;
}

SparseMatrix active_rows(const SparseMatrix& factor, const std::vector<State>& states)
{
  std::vector<Eigen::Triplet<double>> entries;
  int row = 0;
  for (std::size_t i = 0; i < states.size(); i++) {
    if (states[i] == State::open) continue;
    entries.emplace_back(row++, static_cast<int>(2 * i), 1.0);
    entries.emplace_back(row++, static_cast<int>(2 * i + 1), 1.0);
  }
  SparseMatrix select(row, factor.rows());
  select.setFromTriplets(entries.begin(), entries.end());
  return select * factor;
}

SparseMatrix unit_diagonal(const SparseMatrix& c)
{
  Eigen::VectorXd scale(c.cols());
  for (int j = 0; j < c.cols(); j++) {
    const double norm = c.col(j).norm();
    scale(j) = norm > 0.0 ? 1.0 / norm : 0.0;
  }
  return c * scale.asDiagonal();
}

double predicted_rate(const Spectrum& scaled)
{
  if (scaled.rank == 0) return NAN;
  const double contraction = std::max(0.0, 1.0 - scaled.smallest_nonzero);
  return contraction * contraction;
}

namespace {

// Least-squares slope of y against x.
double slope(const std::vector<double>& x, const std::vector<double>& y)
{
  const double n = static_cast<double>(x.size());
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); i++) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double spread = n * sxx - sx * sx;
  return spread > 0.0 ? (n * sxy - sx * sy) / spread : NAN;
}

}  // namespace

TailFit fit_tail(const std::vector<TracePoint>& trace, double from_seconds)
{
  TailFit fit;
  std::vector<double> sweeps, seconds, best_log;
  double best = INFINITY;
  for (const TracePoint& p : trace) {
    best = std::min(best, p.error);
    if (p.seconds < from_seconds) continue;
    sweeps.push_back(p.sweeps);
    seconds.push_back(p.seconds);
    best_log.push_back(std::log10(best));
  }
  if (sweeps.size() < 2) {
    fit.rate_per_sweep = fit.decades_per_second = NAN;
    return fit;
  }
  fit.rate_per_sweep = std::pow(10.0, slope(sweeps, best_log));
  fit.decades_per_second = -slope(seconds, best_log);
  return fit;
}

double best_error_within(const std::vector<TracePoint>& trace, double seconds)
{
  double best = NAN;
  for (const TracePoint& p : trace)
    if (p.seconds <= seconds && !(p.error >= best)) best = p.error;
  return best;
}

const TracePoint* first_reaching(const std::vector<TracePoint>& trace, double target)
{
  for (const TracePoint& p : trace)
    if (p.error <= target) return &p;
  return nullptr;
}

}  // namespace peers
