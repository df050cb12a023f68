// A semismooth Newton method for the 2D Coulomb–Signorini problem of a solve's contacts, and
// the polish that puts it behind Gauss–Seidel's sweeps (GaussSeidelSettings::newton_polish).
//
// The equation is Fischer–Burmeister's on the law as a cone complementarity, K ∋ p ⊥ û ∈ K*,
// K = {|p_t| <= mu p_n}, û = (u_n + mu |u_t|, u_t) (De Saxcé's), u = u_k + W (p - p_k) the law
// velocities. In 2D K has two edges and the law is two scalar pairs per contact,
//   W_nn (mu p_n ± p_t) >= 0  ⊥  u_n + 2 mu max(±u_t, 0) >= 0,
// each solved by phi(a, b) = a + b - sqrt(a^2 + b^2) = 0. Chosen over Alart–Curnier's projection
// (the sweep's own local map, piecewise affine): that one was tried first, and on the corpus's
// mu 2 stall steps its line search, on the kinks of its residual, refused the first step or
// stalled within a factor 2 of the start; Fischer–Burmeister's |phi|^2 is smooth but for |u_t|
// (Siconos's fc3d_nsn_fb solves the same function).
// Globally, Newton is weak (fc3d_nsn_fb misses most hard problems at 1e-3 from r = 0, and this one
// stalls from the sweeps' iterate at 1e-3): the sweeps bring the iterate near the answer first.
#pragma once

#include <vector>

#include "cd/contact.h"
#include "cd/solver.h"

namespace cd {

struct NewtonSolve {
  int iterations = 0;      // Newton steps taken (one sparse factorisation each)
  double start = 0.0;      // |phi| over the contacts' pairs at the start (m/s)
  double residual = 0.0;   // and at the end
  bool converged = false;  // |phi| at round-off of the contacts' velocity scale
};

// sum over the contacts of |W_ii (p_i - proj_K(p_i - W_ii^-1 u_i))|^2 (m^2/s^2), Alart–Curnier's
// residual with the sweep's parameters: what a sweep would change, without sweeping (a quadratic
// norm's numerator). The polish keeps or undoes its Newton steps by it.
double alart_curnier_residual_sq(const std::vector<Contact>& contacts, const std::vector<BodyVelocity>& velocity);

// Newton steps on the contacts' problem, each solving the law linearised at the iterate with
// W_ii + rho on the diagonal (rho = `proximal` W_ii: where a loop of sticking contacts makes W
// singular, the step nearest the iterate; the answer is the law's own). Each step factorises the
// sparse generalized Jacobian (Eigen's SparseLU, COLAMD ordering) and searches back along the
// direction until |Phi| falls (Armijo); the solve stops at round-off, after `max_iterations`,
// when no step lowers |Phi|, or with `stop_when_slow` after a step that did not halve it. The
// impulses and velocities end at the best iterate.
struct NewtonSettings {
  int max_iterations = 50;
  double proximal = 1e-4;
  bool stop_when_slow = false;
};
NewtonSolve solve_newton(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                         const NewtonSettings& settings = {});

// The polish of one Gauss–Seidel solve: after a full sweep, once first_after sweeps are spent and
// the norm is within ten times the tolerance, solve_newton on every contact, stopping when a
// step is slow; its result is kept if it lowers alart_curnier_residual_sq tenfold, else undone
// and the next polish waits twice as many sweeps. One rank only: with an exchange (a
// domain-decomposed run) it does nothing.
class NewtonPolish {
 public:
  NewtonPolish(const SolverSettings& settings, SweepExchange* exchange);

  // After a full sweep that did not end the solve: true if a polish changed the impulses.
  bool act(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, SolveReport& report);

 private:
  // Sweeps before the first polish (most solves end before: a factorisation costs about as much
  // as hundreds of sweeps), and between polishes after one that was kept; doubled after one that
  // was not.
  static constexpr int first_after = 100;
  // The norm a polish waits for (and ten times the tolerance): from the sweeps' iterate at 1e-5
  // Newton meets 1e-6 in a few steps on the committed mu 2 stall step, from theirs at 1e-3 it
  // stalls (tests/peers/test_peers.cpp).
  static constexpr double start_below = 1e-5;
  static constexpr int every = 8;
  static constexpr int newton_steps = 10;
  // A polish is kept if it brings the residual below this fraction of what it was: less, and
  // the sweeps' iterate is worth more than Newton's (its states nearer the answer's).
  static constexpr double kept_below = 0.1;
  bool on_;
  double start_;
  int wait_ = 0;
  int last_ = 0;
  std::vector<Local2> before_;
  std::vector<BodyVelocity> velocity_before_;
};

}  // namespace cd
