// What bounds a solve on a local problem (doc/peer_limits.md): the structure of W, whether the
// answer's impulses are unique, and how fast our sweeps converge.
//
// W = B B^T, B = H M^(-1/2) / sqrt(s): H maps the bodies' velocities (vx, vy, spin of each grain
// the contacts touch, the world left out) to the contacts' local velocities, M the grains' masses
// and inertias, s the problem's impulse scale (bench/peers/local_problem.h). So W's rank is B's,
// at most 3 per grain, and W's nonzero eigenvalues are those of the smaller of B B^T and B^T B.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <vector>

#include "cd/contact.h"
#include "local_problem.h"

namespace peers {

using SparseMatrix = Eigen::SparseMatrix<double>;

// B of the contacts (2m rows, per contact [normal, tangent]; 3 columns per grain), scaled so
// that B B^T is the local problem's W at impulse scale `impulse_scale`.
struct Mobility {
  SparseMatrix factor;  // B
  int grains = 0;       // bodies other than the world with a nonzero inverse mass
};
Mobility mobility(const std::vector<cd::Contact>& contacts, double impulse_scale);

// Largest |B B^T - W| over W's entries, relative to W's largest entry: B's check against the
// problem's own W.
double factor_mismatch(const Mobility& mobility, const LocalProblem& problem);

// The nonzero spectrum of C C^T for a sparse C (dense eigenvalues of the smaller Gram matrix).
// An eigenvalue is counted zero below zero_threshold times the largest; both sides of that cut
// are reported, so that a rank is read with the gap that decides it. A Gram matrix over
// `dense_limit` rows is not formed: the rank is then sparse_rank's and the eigenvalues NaN.
struct Spectrum {
  int rows = 0;            // C's rows: the size of C C^T
  int rank = 0;            // eigenvalues above the cut
  int null_dimension = 0;  // rows - rank: C C^T's null space
  double largest = 0.0;    // eigenvalue
  double smallest_nonzero = 0.0;
  double largest_zero = 0.0;  // the largest eigenvalue under the cut (0 if none)
  double range_condition() const { return rank > 0 ? smallest_nonzero / largest : 0.0; }
};
constexpr double zero_threshold = 1e-10;
Spectrum gram_spectrum(const SparseMatrix& c, int dense_limit = 6000);

// C's rank by a sparse QR factorization (Eigen's SparseQR, COLAMD ordering, its default
// threshold on R's diagonal): for the problems whose Gram matrix is too large to be dense.
int sparse_rank(const SparseMatrix& c);

// Each contact's state at an answer r: open (r_n at most `tolerance` times the largest r_n),
// sliding (|r_t| at least mu r_n (1 - tolerance)), else sticking.
enum class State { open, stick, slide };
std::vector<State> contact_states(const LocalProblem& problem, const std::vector<double>& reaction, double tolerance);

// The directions an answer's impulses can move in without leaving its law's face: both of a
// sticking contact's, a sliding contact's along its cone edge (1, r_t / r_n), none of an open
// one's. Columns of a 2m x k matrix.
SparseMatrix free_directions(const LocalProblem& problem, const std::vector<double>& reaction,
                             const std::vector<State>& states);

// The rows of B of the contacts that are not open: the active block W_AA = B_A B_A^T.
SparseMatrix active_rows(const SparseMatrix& factor, const std::vector<State>& states);

// C's columns scaled to unit norm. With C = B^T P, the Gram matrix of the result is
// D^(-1/2) P^T W P D^(-1/2) (D: P^T W P's diagonal), the operator whose Jacobi iteration a linear
// Gauss–Seidel sweep on the answer's faces squares (exactly for a consistently ordered matrix; an
// estimate otherwise).
SparseMatrix unit_diagonal(const SparseMatrix& c);

// Gauss–Seidel's rate per sweep on the faces, estimated from that spectrum: (1 - lambda_min)^2.
double predicted_rate(const Spectrum& scaled);

// A solve's error after each full sweep, and the straight line through the tail of its best
// error so far: log10(best error) against sweeps and against seconds, from `from_seconds` of
// solver time to the run's end.
struct TracePoint {
  int sweeps = 0;
  double seconds = 0.0;  // solver time (error checks left out)
  double error = 0.0;
  double contact_updates = 0.0;  // local solves so far (cd::SolveReport)
  int block_solves = 0;          // the stall rescue's so far, kept blocks' included
  int cold_restarts = 0;         // the stall rescue's so far
};
struct TailFit {
  double rate_per_sweep = 1.0;      // best error's factor per sweep (1: no progress)
  double decades_per_second = 0.0;  // its fall per second of solver time
};
TailFit fit_tail(const std::vector<TracePoint>& trace, double from_seconds);

// The best error reached within `seconds` of solver time (NaN before the first full sweep).
double best_error_within(const std::vector<TracePoint>& trace, double seconds);

// The first full sweep whose error reached `target` (nullptr if none did).
const TracePoint* first_reaching(const std::vector<TracePoint>& trace, double target);

}  // namespace peers
