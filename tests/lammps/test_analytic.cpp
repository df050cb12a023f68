// Analytic cases run through LAMMPS: a disk on an incline, impacts across the periodic
// boundary and on a wall-segment end.
#include <gtest/gtest.h>

#include <cmath>

#include "fmt/format.h"
#include "lammps_session.h"
#include "shared_decks.h"

namespace {

using cdtest::LammpsSession;

constexpr double d = 5e-4;  // m
constexpr double r = 0.5 * d;
constexpr double g = 9.81;
constexpr double deg = M_PI / 180.0;

// One disk resting on the floor y = 0 of an x-periodic box, gravity tilted by `angle`.
void incline_deck(LammpsSession& s, double angle, double mu)
{
  s.commands(cdtest::disk_preamble);
  s.commands(fmt::format(R"(
boundary p f p
region box block 0 {L} -{L} {L} -{r} {r}
create_box 1 box
create_atoms 1 single {L2} {r} 0
set atom 1 diameter {d} density/disc 2500
neighbor {skin} bin
timestep 1e-5
fix grav all gravity {g} vector {sx} {sy} 0
fix cd all contact/dynamics {mu} 0.5 wall yplane 0.0 {mu} 0.5 tolerance 1e-12
fix 2d all enforce2d
)",
                         fmt::arg("L", 20 * d), fmt::arg("L2", 10 * d), fmt::arg("r", r), fmt::arg("d", d),
                         fmt::arg("skin", 0.2 * d), fmt::arg("g", g), fmt::arg("sx", std::sin(angle)),
                         fmt::arg("sy", -std::cos(angle)), fmt::arg("mu", mu)));
}

struct InclineCase {
  double angle_deg;
  double mu;
};

class Incline : public ::testing::TestWithParam<InclineCase> {};

// Rolls without slip with a = 2/3 g sin(theta) when tan(theta) <= 3 mu; otherwise slides with
// a = g (sin - mu cos) and spins up with alpha = 2 mu g cos / r (torque mu N r, I = m r^2 / 2).
TEST_P(Incline, AccelerationAndSpinMatchRollingOrSliding)
{
  const double angle = GetParam().angle_deg * deg, mu = GetParam().mu;
  LammpsSession s;
  incline_deck(s, angle, mu);
  const int steps = 2000;
  s.commands(fmt::format("run {}", steps));
  const double t = steps * 1e-5;
  const bool rolls = std::tan(angle) <= 3.0 * mu;
  const double a = rolls ? 2.0 / 3.0 * g * std::sin(angle) : g * (std::sin(angle) - mu * std::cos(angle));
  const double alpha = rolls ? -a / r : -2.0 * mu * g * std::cos(angle) / r;
  // The theta-method is exact for constant forces; what remains is the solver tolerance.
  EXPECT_NEAR(s.v(1, 0), a * t, 1e-8 * a * t);
  EXPECT_NEAR(s.spin(1), alpha * t, 1e-8 * std::abs(alpha * t));
  EXPECT_NEAR(s.v(1, 1), 0.0, 1e-12);
  EXPECT_NEAR(s.x(1, 1), r, 1e-12 * r);
}

INSTANTIATE_TEST_SUITE_P(RollOrSlide, Incline,
                         ::testing::Values(InclineCase{20.0, 0.5}, InclineCase{30.0, 0.1},
                                           // either side of the threshold tan(theta) = 3 mu = 0.6
                                           InclineCase{29.0, 0.2}, InclineCase{32.0, 0.2}));

// Head-on impact of two disks that touch through the periodic boundary x = 0 = L.
TEST(PeriodicBoundary, ImpactAcrossTheBoundaryFollowsNewtonRestitution)
{
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  const double v = 0.2, e = 0.5;
  s.commands(cdtest::periodic_impact_deck(d, v, e));
  EXPECT_NEAR(s.v(1, 0), v * (1 - e) / 2, 1e-12);
  EXPECT_NEAR(s.v(2, 0), v * (1 + e) / 2, 1e-12);
  EXPECT_EQ(s.fix("cd")->compute_vector(2), 1.0) << "the pair must be found exactly once";
}

struct SegmentEndCase {
  double disk_x;  // disk centre x (box length 20 d, segment at x = wall_x)
  double wall_x;
  double offset_x;  // disk centre minus wall, through the periodic boundary if needed
};

class SegmentEnd : public ::testing::TestWithParam<SegmentEndCase> {};

// A disk falling on the top end of a vertical segment rebounds along the line from the end
// point to its centre: v' = v - (1 + e)(v.n) n (frictionless wall).
TEST_P(SegmentEnd, ImpactOnEndPointReflectsAlongItsNormal)
{
  const auto [disk_x, wall_x, offset] = GetParam();
  const double L = 20 * d, top = 5 * d, v = 0.3, e = 0.5;
  const double height = std::sqrt(r * r - offset * offset);
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  s.commands(fmt::format(R"(
boundary p f p
region box block 0 {L} 0 {L} -{r} {r}
create_box 1 box
create_atoms 1 single {x} {y} 0
set atom 1 diameter {d} density/disc 2500 vy -{v}
neighbor {skin} bin
timestep 1e-6
fix cd all contact/dynamics 0.5 0.5 wall segment {wx} 0 {wx} {top} 0.0 {e} tolerance 1e-12
fix 2d all enforce2d
run 1
)",
                         fmt::arg("L", L), fmt::arg("r", r), fmt::arg("x", disk_x), fmt::arg("y", top + height),
                         fmt::arg("d", d), fmt::arg("v", v), fmt::arg("skin", 0.2 * d), fmt::arg("wx", wall_x),
                         fmt::arg("top", top), fmt::arg("e", e)));
  // Moreau–Jean detects the contact at the predicted configuration y_m = y_n - (1 - theta) dt v.
  const double height_m = height - 0.5 * 1e-6 * v;
  const double distance_m = std::sqrt(offset * offset + height_m * height_m);
  const double nx = offset / distance_m, ny = height_m / distance_m;
  const double vn = -v * ny;
  EXPECT_NEAR(s.v(1, 0), -(1 + e) * vn * nx, 1e-10);
  EXPECT_NEAR(s.v(1, 1), -v - (1 + e) * vn * ny, 1e-10);
  EXPECT_NEAR(s.spin(1), 0.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(InsideAndAcrossPeriodicBoundary, SegmentEnd,
                         ::testing::Values(SegmentEndCase{10 * d + 0.3 * r, 10 * d, 0.3 * r},
                                           SegmentEndCase{20 * d - 0.4 * r, 0.0, -0.4 * r}));

}  // namespace
