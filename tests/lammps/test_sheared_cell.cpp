// Tilted and sheared periodic boxes (LAMMPS's triclinic box, fix deform xy erate ... remap v):
// walls imaged along the tilt, and images across the sheared side moving with the box.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "domain.h"
#include "fmt/format.h"
#include "lammps_session.h"

namespace {

using cdtest::LammpsSession;

constexpr double g = 9.81;

// A y-periodic box 10 mm square tilted by half its length (xy = 5 mm). A ledge spans x 1 to 4 mm
// at y = 9.5 mm; its image across the bottom side spans x 6 to 9 mm at y = -0.5 mm. A disk of
// radius 1 mm dropped at x = 2.5 mm, y = 5 mm passes beside the image, crosses the bottom side
// (LAMMPS moves it to x + xy = 7.5 mm at the top), passes beside the ledge 3.5 mm away and
// comes to rest on the image: at x = 7.5 mm, y = -0.5 + 1 = 0.5 mm. Imaged as in an orthogonal
// box, the ledge's image would lie under the disk's first fall (x 1 to 4 mm) and stop it there.
TEST(TiltedBox, FallingDiskRestsOnTheSegmentUnderIt)
{
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  s.commands(R"(
boundary p p p
region box prism 0 0.01 0 0.01 -0.001 0.001 0.005 0 0
create_box 1 box
create_atoms 1 single 0.0025 0.005 0
set atom 1 diameter 0.002 density/disc 2500
neighbor 2e-4 bin
timestep 1e-5
fix grav all gravity 9.81 vector 0 -1 0
fix cd all contact/dynamics 0.5 0.0 tolerance 1e-12 wall segment 0.001 0.0095 0.004 0.0095 0.5 0.0
fix 2d all enforce2d
run 8000
)");
  // The fall of 14.5 mm takes 54 ms; 80 ms run.
  EXPECT_NEAR(s.x(1, 0), 0.0075, 1e-12);
  // Landing, the predictor carries the disk up to (1 - theta) dt v into the ledge's image at
  // the impact speed sqrt(2 g h), and a rigid contact keeps that overlap (inelastic here).
  const double landing_overlap = 0.5 * 1e-5 * std::sqrt(2 * g * 0.0145);
  EXPECT_LE(s.x(1, 1), 0.0005);
  EXPECT_GE(s.x(1, 1), 0.0005 - landing_overlap);
  EXPECT_NEAR(s.v(1, 1), 0.0, 1e-12);
  EXPECT_LT(std::sqrt(2 * 0.0145 / g), 0.06);  // the fall ends within the 80 ms run
}

// A periodic box L square of 1 mm disks (radius r), sheared at `rate` (xy erate, remap v) with
// time step dt: the disks created by `atoms`, then the fix with `fix_arguments`, run `steps`.
void sheared_cell(LammpsSession& s, double rate, double dt, const std::string& atoms, const std::string& fix_arguments,
                  int steps)
{
  constexpr double L = 0.01, r = 5e-4;
  s.commands(cdtest::disk_preamble);
  s.commands(fmt::format(R"(
boundary p p p
region box prism 0 {L} 0 {L} -{r} {r} 0 0 0
create_box 1 box
{atoms}
set group all diameter {d} density/disc 2500
neighbor {skin} bin
timestep {dt}
fix shear all deform 1 xy erate {rate} remap v
fix cd all contact/dynamics {fix}
fix 2d all enforce2d
run {steps}
)",
                         fmt::arg("L", L), fmt::arg("r", r), fmt::arg("atoms", atoms), fmt::arg("d", 2 * r),
                         fmt::arg("skin", 0.4 * r), fmt::arg("dt", dt), fmt::arg("rate", rate),
                         fmt::arg("fix", fix_arguments), fmt::arg("steps", steps)));
}

// Two disks touch across the top side of a box sheared at rate 10/s (xy erate, remap v): disk
// 2 at (x_b, r), disk 1 where the image of disk 2 across the top, at (x_b + xy, L + r), touches
// it along n = (1, -1)/sqrt 2. Both are at rest, but the image moves at w = (rate L, 0) with
// the box: it strikes disk 1 with the normal velocity w.n. Frictionless, restitution e: disk 1
// leaves at (1+e)/2 (w.n) n and disk 2 at the opposite, n taken at the predicted configuration,
// where the image has moved (1 - theta) dt w.
TEST(ShearedBox, ImageAcrossTheShearedSideStrikesWithTheBoxVelocity)
{
  constexpr double L = 0.01, r = 5e-4, rate = 10.0, e = 0.5, dt = 1e-5;
  const double xb = 0.004, xa = xb + std::sqrt(2.0) * r, ya = L + r - std::sqrt(2.0) * r;
  LammpsSession s;
  sheared_cell(s, rate, dt, fmt::format("create_atoms 1 single {} {} 0\ncreate_atoms 1 single {} {} 0", xa, ya, xb, r),
               fmt::format("0.0 {} tolerance 1e-12", e), 1);
  const double w = rate * L;
  EXPECT_DOUBLE_EQ(s.lmp->domain->h_rate[5], w);
  const double image_x = xb + 0.5 * dt * w;  // theta 0.5; xy = 0 at the start of the step
  const double nx = xa - image_x, ny = ya - (L + r), length = std::hypot(nx, ny);
  const double closing = w * nx / length;  // w.n > 0: the image drives into disk 1
  const double speed = 0.5 * (1 + e) * closing;
  EXPECT_NEAR(s.v(1, 0), speed * nx / length, 1e-12);
  EXPECT_NEAR(s.v(1, 1), speed * ny / length, 1e-12);
  EXPECT_NEAR(s.v(2, 0), -speed * nx / length, 1e-12);
  EXPECT_NEAR(s.v(2, 1), -speed * ny / length, 1e-12);
  // Met where LAMMPS placed it (the box at the start of the step), the image would send disk 1
  // off measurably differently: the check above tells the two apart.
  const double start_nx = xa - xb, start_length = std::hypot(start_nx, ny);
  const double start_vx = 0.5 * (1 + e) * w * start_nx / start_length * start_nx / start_length;
  EXPECT_GT(std::fabs(start_vx - s.v(1, 0)), 1e-6);
}

// A disk falls freely at 0.1 m/s through the bottom side of a box sheared at 10/s. LAMMPS wraps
// it to the top, into the image that moves with the box at w = rate L along x, and gives it that
// velocity (remap v): from then on it moves with its image, x = x0 + xy(t) = x0 + w t, where the
// step meets images (at the predicted configuration, as every ghost, not where the box stood at
// the start of the step, (1 - theta) dt w behind).
TEST(ShearedBox, DiskCrossingTheShearedSideMovesWithItsImage)
{
  constexpr double L = 0.01, rate = 10.0, dt = 1e-5, fall = 0.1, x0 = 0.003, y0 = 0.001;
  constexpr int steps = 3000;  // 30 ms: across the side at 10 ms, the tilt 3 mm (below half of L)
  LammpsSession s;
  sheared_cell(s, rate, dt,
               fmt::format("create_atoms 1 single {} {} 0\nvelocity all set 0 -{} 0 units box", x0, y0, fall),
               "0.5 0.5 tolerance 1e-12", steps);
  const double w = rate * L, elapsed = steps * dt;
  EXPECT_NEAR(s.lmp->domain->xy, w * elapsed, 1e-15);
  EXPECT_NEAR(s.v(1, 0), w, 1e-15);
  EXPECT_NEAR(s.v(1, 1), -fall, 1e-15);
  EXPECT_NEAR(s.x(1, 0), x0 + w * elapsed, 1e-12);
  EXPECT_NEAR(s.x(1, 1), y0 - fall * elapsed + L, 1e-12);
}

}  // namespace
