// The seam proven by a peer (doc/peer_seam.md): Siconos's solvers, registered by
// name from outside the core (bench/peers/siconos_contact_solver.cpp), step a small chute through
// cd::MoreauJeanStep (the testbed's bed, tilted) to the trajectory of ours.
//
// The bound. A solve stopped at a tolerance leaves an error; no two methods leave the same one,
// and a granular flow amplifies any difference (a contact opening a step earlier), so no fixed
// distance in m/s is the tolerance's. Each method's own error is measured instead: its distance
// from itself solving every step ten times tighter (for a linear convergence, (10/9) of its
// error). Two methods converging to one solution are apart by at most the sum of their errors;
// the test allows twice the sum of the measured distances, step by step. A peer solving another
// problem (impulses in the wrong units, a wrong W, the warm start lost) is apart by the step's
// whole contact velocity change, orders of magnitude more.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cd/solver_registry.h"
#include "testbed/granular_bed.h"

namespace {

constexpr double slack = 2.0;  // over the sum of the two methods' measured errors

// 200 disks, 20 d wide and about 10 d deep over a rough base (its lowest layer immobile), tilted
// by `slope` and flowing for 0.02 s (200 steps of ours at the deck's tolerance).
testbed::BedSpec chute_spec(double mu, double slope)
{
  testbed::BedSpec spec;
  spec.disk_count = 200;
  spec.cell_length = 20.0;
  spec.immobile_layer = 1.0;
  spec.slope = slope;
  spec.dt = 1.0e-4;  // the chute deck's
  spec.grain_law = {mu, 0.0};
  spec.wall_law = {mu, 0.0};
  spec.settle_steps = 200;
  spec.solver.tolerance = 1.0e-3;
  spec.solver.max_iterations = 100000;
  return spec;
}

cd::SolverSettings solver(const std::string& method, double tolerance)
{
  cd::SolverSettings settings;
  settings.method = method;
  settings.tolerance = tolerance;
  settings.max_iterations = 100000;
  return settings;
}

// RMS over the disks of the velocity difference, spin as r * spin (m/s).
double velocity_distance(const testbed::GranularBed& a, const testbed::GranularBed& b)
{
  double sum = 0.0;
  for (std::size_t k = 0; k < a.disks().size(); k++) {
    const cd::BodyVelocity &va = a.velocities()[k], &vb = b.velocities()[k];
    const double r = a.disks()[k].radius;
    sum += std::pow(va.vx - vb.vx, 2) + std::pow(va.vy - vb.vy, 2) + std::pow(r * (va.spin - vb.spin), 2);
  }
  return std::sqrt(sum / static_cast<double>(a.disks().size()));
}

// The largest distance between a disk's two positions, in d (across the periodic side).
double position_distance(const testbed::GranularBed& a, const testbed::GranularBed& b)
{
  double largest = 0.0;
  const double length = a.length_x();
  for (std::size_t k = 0; k < a.disks().size(); k++) {
    double dx = a.disks()[k].x - b.disks()[k].x;
    dx -= length * std::round(dx / length);
    largest = std::max(largest, std::hypot(dx, a.disks()[k].y - b.disks()[k].y));
  }
  return largest / a.spec().mean_diameter;
}

// One method stepping the chute at a tolerance and ten times tighter, from the same state.
struct Pair {
  Pair(const testbed::BedSpec& spec, const std::string& method, double tolerance)
      : at(std::make_unique<testbed::GranularBed>(spec)), tighter(std::make_unique<testbed::GranularBed>(spec))
  {
    at->use_solver(solver(method, tolerance));
    tighter->use_solver(solver(method, tolerance / 10.0));
  }
  cd::SolveReport step()
  {
    tighter->step();
    return at->step();
  }
  double own_error() const { return velocity_distance(*at, *tighter); }
  std::unique_ptr<testbed::GranularBed> at, tighter;
};

struct Agreement {
  int steps = 0;
  double worst_ratio = 0.0;  // max over steps of distance / (sum of own errors)
  double velocity = 0.0;     // at the last step (m/s)
  double position = 0.0;     // at the last step (d)
  double own_errors = 0.0;   // their sum at the last step (m/s)
};

// Steps ours and the peer `steps` times, each at `tolerance` and ten times tighter; checks every
// step and returns the agreement.
Agreement step_both(const testbed::BedSpec& spec, const std::string& peer, double tolerance, int steps)
{
  Pair ours(spec, "gauss_seidel", tolerance), theirs(spec, peer, tolerance);
  Agreement agreement;
  const double contact_change = spec.gravity * spec.dt;  // the scale of a step's velocity change
  for (int n = 1; n <= steps; n++) {
    ours.step();
    const cd::SolveReport report = theirs.step();
    EXPECT_TRUE(report.converged) << peer << " step " << n << ": error " << report.residual;
    EXPECT_LE(report.residual, tolerance) << peer << " step " << n;
    const double apart = velocity_distance(*ours.at, *theirs.at);
    const double own = ours.own_error() + theirs.own_error();
    EXPECT_LE(apart, slack * own) << peer << " step " << n << ": apart " << apart / contact_change
                                  << " g dt, own errors " << own / contact_change << " g dt";
    agreement.steps = n;
    agreement.worst_ratio = std::max(agreement.worst_ratio, apart / own);
    agreement.velocity = apart;
    agreement.position = position_distance(*ours.at, *theirs.at);
    agreement.own_errors = own;
    if (n == 1 || n % 5 == 0)
      std::printf("%s mu %g, tolerance %g, step %d: apart %.3g g dt (%.3g d), own errors %.3g g dt, worst ratio %.3f\n",
                  peer.c_str(), spec.grain_law.mu, tolerance, n, apart / contact_change, agreement.position,
                  own / contact_change, agreement.worst_ratio);
  }
  return agreement;
}

TEST(PeerSeam, SiconosSolversAreRegisteredByNameOutsideTheCore)
{
  const std::vector<std::string> names = cd::solver_names();
  for (const char* name : {"gauss_seidel", "siconos_fc2d_nsgs", "siconos_fc3d_nsn_fb"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  cd::SolverSettings settings = solver("siconos_fc2d_nsgs", 1e-4);
  settings.norm = cd::ConvergenceNorm::maximum;
  EXPECT_EQ(cd::check(settings),
            "siconos_fc2d_nsgs stops on Siconos's own error: norm must be quadratic (the default)");
}

// One step at 1e-6: the peers' answers within their own errors of ours, the 2D NSGS and the 3D
// one on the embedded problem alike, at mu 0.5 (24 degrees) and 0.05 (20 degrees).
TEST(PeerSeam, OneStepOfTheChuteAgreesWithinTheMethodsOwnErrors)
{
  for (const double mu : {0.5, 0.05})
    for (const char* peer : {"siconos_fc2d_nsgs", "siconos_fc3d_nsgs"}) {
      const Agreement one = step_both(chute_spec(mu, mu > 0.1 ? 24.0 : 20.0), peer, 1e-6, 1);
      EXPECT_GT(one.velocity, 0.0) << "the same numbers: not another method";
    }
}

// 20 steps at 1e-4 (mu 0.5, 24 degrees), every step within the spread of the two methods' errors.
TEST(PeerSeam, TheChuteFollowsTheSameTrajectoryWithinTheMethodsOwnErrors)
{
  step_both(chute_spec(0.5, 24.0), "siconos_fc2d_nsgs", 1e-4, 20);
}

}  // namespace
