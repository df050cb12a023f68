// Packings at rest stay at rest, and their contact impulses carry exactly their weight.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fmt/format.h"
#include "lammps_session.h"

namespace {

using cdtest::LammpsSession;

constexpr double d = 5e-4, r = 0.5 * d, g = 9.81, dt = 1e-5, density = 2500.0;

struct Position {
  double x, y;
};

void build_packing(LammpsSession& s, const std::vector<Position>& disks, double mu)
{
  s.commands(cdtest::disk_preamble);
  s.commands(fmt::format(R"(
boundary p f p
region box block 0 {L} 0 {L} -{r} {r}
create_box 1 box
)",
                         fmt::arg("L", 20 * d), fmt::arg("r", r)));
  for (const Position& p : disks) s.commands(fmt::format("create_atoms 1 single {} {} 0", p.x, p.y));
  s.commands(fmt::format(R"(
set group all diameter {d} density/disc {rho}
neighbor {skin} bin
timestep {dt}
fix grav all gravity {g} vector 0 -1 0
fix cd all contact/dynamics {mu} 0.5 wall yplane 0.0 {mu} 0.5 tolerance 1e-12 max_iterations 100000
fix 2d all enforce2d
)",
                         fmt::arg("d", d), fmt::arg("rho", density), fmt::arg("skin", 0.2 * d), fmt::arg("dt", dt),
                         fmt::arg("g", g), fmt::arg("mu", mu)));
}

// Largest displacement of any disk from where it was built, in diameters.
double largest_drift(const LammpsSession& s, const std::vector<Position>& disks)
{
  double drift = 0.0;
  for (std::size_t k = 0; k < disks.size(); k++) {
    const int id = static_cast<int>(k) + 1;
    drift = std::max(drift, std::hypot(s.x(id, 0) - disks[k].x, s.x(id, 1) - disks[k].y));
  }
  return drift / d;
}

// Sum of the wall's normal and tangential impulses over one step, from the local output.
Position wall_impulse(const LammpsSession& s)
{
  LAMMPS_NS::Fix* fix = s.fix("cd");
  Position sum{0.0, 0.0};
  for (int row = 0; row < fix->size_local_rows; row++) {
    const double* contact = fix->array_local[row];
    if (contact[2] != 1.0) continue;  // wall index column
    sum.x += contact[4];              // tangential
    sum.y += contact[3];              // normal
  }
  return sum;
}

void expect_at_rest_carrying_weight(LammpsSession& s, const std::vector<Position>& disks)
{
  s.commands("run 10000");
  // Converged impulses cancel gravity to ~tolerance * g dt per step: over 1e4 steps the drift
  // stays far below 1e-9 d, while a restitution or candidate-selection error would move disks
  // by at least g dt^2 ~ 1e-9 m ~ 2e-6 d in one step.
  EXPECT_LT(largest_drift(s, disks), 1e-9);
  const double weight = disks.size() * M_PI * r * r * density * g;
  const Position floor = wall_impulse(s);
  EXPECT_NEAR(floor.y / dt, weight, 1e-7 * weight);
  EXPECT_NEAR(floor.x / dt, 0.0, 1e-7 * weight);
  EXPECT_EQ(s.fix("cd")->compute_vector(8), 0.0) << "every step converged";
}

TEST(StaticPacking, ColumnStaysAtRest)
{
  std::vector<Position> column;
  for (int k = 0; k < 10; k++) column.push_back({10 * d, r + k * d});
  LammpsSession s;
  build_packing(s, column, 0.5);
  expect_at_rest_carrying_weight(s, column);
}

// Two disks side by side on the floor carrying a third: the top disk wedges the bottom ones
// apart, and torque balance makes the floor friction equal the disk-disk friction; the pile
// stands if and only if mu >= tan(15 deg) = 2 - sqrt(3) ~ 0.268.
std::vector<Position> three_disk_pyramid()
{
  const double x0 = 8 * d;
  return {{x0, r}, {x0 + d, r}, {x0 + 0.5 * d, r + d * std::sqrt(3.0) / 2.0}};
}

TEST(StaticPacking, PyramidStandsAboveTheCriticalFriction)
{
  const std::vector<Position> pyramid = three_disk_pyramid();
  LammpsSession s;
  build_packing(s, pyramid, 0.28);
  expect_at_rest_carrying_weight(s, pyramid);
}

TEST(StaticPacking, PyramidCollapsesBelowTheCriticalFriction)
{
  const std::vector<Position> pyramid = three_disk_pyramid();
  LammpsSession s;
  build_packing(s, pyramid, 0.25);
  s.commands("run 2000");
  EXPECT_GT(largest_drift(s, pyramid), 1e-3);
}

}  // namespace
