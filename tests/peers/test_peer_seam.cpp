// exploratory
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cd/solver_registry.h"
#include "testbed/granular_bed.h"

namespace {

testbed::BedSpec chute_spec(double mu, double slope, double tolerance)
{
  testbed::BedSpec spec;
  spec.disk_count = 300;
  spec.cell_length = 20.0;
  spec.immobile_layer = 1.0;
  spec.slope = slope;
  spec.dt = 1.0e-4;
  spec.grain_law = {mu, 0.0};
  spec.wall_law = {mu, 0.0};
  spec.settle_steps = 300;
  spec.solver.tolerance = tolerance;
  spec.solver.max_iterations = 100000;
  return spec;
}

struct Distance {
  double position = 0.0;  // max over disks, in d
  double velocity = 0.0;  // rms over disks (m/s)
};

Distance distance(const testbed::GranularBed& a, const testbed::GranularBed& b)
{
  Distance d;
  double sum = 0.0;
  const double length = a.length_x(), diameter = a.spec().mean_diameter;
  for (std::size_t k = 0; k < a.disks().size(); k++) {
    double dx = a.disks()[k].x - b.disks()[k].x;
    dx -= length * std::round(dx / length);
    d.position = std::max(d.position, std::hypot(dx, a.disks()[k].y - b.disks()[k].y) / diameter);
    const cd::BodyVelocity &va = a.velocities()[k], &vb = b.velocities()[k];
    const double r = a.disks()[k].radius;
    sum += std::pow(va.vx - vb.vx, 2) + std::pow(va.vy - vb.vy, 2) + std::pow(r * (va.spin - vb.spin), 2);
  }
  d.velocity = std::sqrt(sum / a.disks().size());
  return d;
}

TEST(Explore, Growth)
{
  for (double tolerance : {1e-4, 1e-6}) {
    const testbed::BedSpec spec = chute_spec(0.5, 24.0, tolerance);
    testbed::GranularBed ours(spec), tighter(spec), siconos(spec);
    cd::SolverSettings s = spec.solver;
    ours.use_solver(s);
    s.tolerance = tolerance / 10;
    tighter.use_solver(s);
    s.tolerance = tolerance;
    s.method = "siconos_fc2d_nsgs";
    siconos.use_solver(s);
    std::printf("tol %g max speed %g\n", tolerance, ours.max_speed());
    const double g_dt = spec.gravity * spec.dt;
    for (int n = 1; n <= 100; n++) {
      const cd::SolveReport a = ours.step(), b = tighter.step(), c = siconos.step();
      if (n == 1 || n == 2 || n == 5 || n == 10 || n == 20 || n == 50 || n == 100) {
        const Distance self = distance(ours, tighter), peer = distance(ours, siconos), pt = distance(tighter, siconos);
        std::printf("n %3d self %.3g d %.3g gdt | peer %.3g d %.3g gdt | tight-peer %.3g d %.3g gdt | it %d %d %d res %.2g\n",
                    n, self.position, self.velocity / g_dt, peer.position, peer.velocity / g_dt, pt.position,
                    pt.velocity / g_dt, a.iterations, b.iterations, c.iterations, c.residual);
      }
    }
  }
}

}  // namespace
