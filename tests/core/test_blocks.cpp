// The sweep of a decomposed run reproduced on one rank (testbed::sweep_in_blocks): blocks sweep from the
// same velocities and their changes add up. Where two blocks push on one body at once the
// iteration differs from Gauss–Seidel; where it converges, it reaches the same solution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cd/gauss_seidel.h"
#include "testbed/emulated_ranks.h"
#include "pile.h"

namespace {

// One disk at rest on the floor, held by two copies of the floor contact, falling at the
// step's free velocity -g dt (e = 0).
struct DoubleFloor {
  double mass = M_PI * radius * radius * density;
  double fall = -gravity * step.dt;
  Pile pile;

  DoubleFloor()
  {
    pile.bodies.reset(2);
    pile.bodies.inertia[1] = {1.0 / mass, 1.0 / (0.5 * mass * radius * radius)};
    pile.bodies.velocity[1] = {0.0, fall, 0.0};
    const cd::Disk disk{0.0, radius, radius};
    for (int copy = 0; copy < 2; copy++) {
      pile.contacts.push_back(cd::prepared_contact(cd::disk_world_geometry(1, disk, 0.0, 0.0, 0.0, 1.0),
                                                   cd::ContactLaw{0.5, 0.0}, pile.bodies, step));
    }
  }
  double vy() const { return pile.bodies.velocity[1].vy; }
};

// In one block the first copy stops the disk and the second has nothing to do. In two blocks
// each copy stops it alone, so the summed changes throw it up at +g dt; next sweep each copy
// releases its impulse and it falls at -g dt: for ever.
TEST(BlockSweep, TwoBlocksPushingOneBodyOvershootAndAlternate)
{
  DoubleFloor one_block;
  cd::sweep(one_block.pile.contacts, one_block.pile.bodies.velocity, {});
  EXPECT_NEAR(one_block.vy(), 0.0, 1e-15);
  EXPECT_NEAR(one_block.pile.contacts[0].impulse.n, -one_block.mass * one_block.fall, 1e-15 * one_block.mass);
  EXPECT_EQ(one_block.pile.contacts[1].impulse.n, 0.0);

  DoubleFloor two_blocks;
  const std::vector<std::size_t> block_ends{1, 2};
  for (int sweep = 1; sweep <= 5; sweep++) {
    testbed::sweep_in_blocks(two_blocks.pile.contacts, block_ends, two_blocks.pile.bodies.velocity, {});
    const double expected = sweep % 2 == 1 ? -two_blocks.fall : two_blocks.fall;
    EXPECT_NEAR(two_blocks.vy(), expected, 1e-12 * -two_blocks.fall) << "sweep " << sweep;
    EXPECT_EQ(two_blocks.pile.bodies.velocity[1].vx, 0.0);
  }
  const cd::SolverSettings settings{1e-6, 50, cd::ConvergenceNorm::quadratic};
  EXPECT_FALSE(testbed::solve_in_blocks(two_blocks.pile.contacts, block_ends, two_blocks.pile.bodies.velocity, settings)
                   .converged);
}

// Frictionless disks of one size stacked on a hexagonal lattice between a floor and two side
// walls, every pair touching, at rest, the step's gravity in their free velocity (e = 0): the
// pile holds, and rest is the only solution (frictionless velocities are unique). Split into
// vertical slabs as ranks split a cell, solved in blocks and in one order to 1e-12: both stop
// the pile to 1e-9 g dt, the blocks by another iteration (748 sweeps against 649: the slabs
// share grains); and one block is the plain sweep, to the round-off of v_start + (v - v_start).
struct WalledStack {
  static constexpr int columns = 8, rows = 6;
  std::vector<cd::Disk> disks;
  cd::BodySet bodies;
  std::vector<cd::Contact> contacts;

  WalledStack()
  {
    for (int row = 0; row < rows; row++)
      for (int column = 0; column < columns - row % 2; column++)
        disks.push_back({(2 * column + row % 2 + 1) * radius, (1.0 + row * std::sqrt(3.0)) * radius, radius});
    const int count = static_cast<int>(disks.size());
    const double mass = M_PI * radius * radius * density;
    bodies.reset(count + 1);
    for (int k = 1; k <= count; k++) {
      bodies.inertia[k] = {1.0 / mass, 1.0 / (0.5 * mass * radius * radius)};
      bodies.velocity[k] = {0.0, -gravity * step.dt, 0.0};
    }
    const cd::ContactLaw law{0.0, 0.0};
    auto add = [&](const cd::ContactGeometry& g) { contacts.push_back(cd::prepared_contact(g, law, bodies, step)); };
    const double right = 2 * columns * radius;
    for (int i = 0; i < count; i++) {
      const cd::Disk& disk = disks[i];
      // disk_world_geometry takes the vector from the wall's nearest point to the centre.
      if (disk.y < 1.5 * radius) add(cd::disk_world_geometry(1 + i, disk, 0.0, disk.y, 0.0, 1.0));
      if (disk.x < 1.5 * radius) add(cd::disk_world_geometry(1 + i, disk, disk.x, 0.0, 1.0, 0.0));
      if (disk.x > right - 1.5 * radius) add(cd::disk_world_geometry(1 + i, disk, disk.x - right, 0.0, -1.0, 0.0));
      for (int j = i + 1; j < count; j++)
        if (std::hypot(disk.x - disks[j].x, disk.y - disks[j].y) < 2.0 * radius + 1e-9)
          add(cd::disk_disk_geometry(1 + i, disk, 1 + j, disks[j]));
    }
  }
};

TEST(BlockSweep, ConvergesToTheGaussSeidelSolution)
{
  WalledStack blocks, plain;
  ASSERT_GT(blocks.contacts.size(), 100u);
  constexpr int slabs = 4;
  const double width = 2 * WalledStack::columns * radius;
  auto slab_of = [&](const cd::Contact& c) {
    return std::min(slabs - 1, static_cast<int>(blocks.disks[c.body_a - 1].x / width * slabs));
  };
  std::stable_sort(blocks.contacts.begin(), blocks.contacts.end(),
                   [&](const cd::Contact& a, const cd::Contact& b) { return slab_of(a) < slab_of(b); });
  std::vector<std::size_t> block_ends;
  for (std::size_t k = 0; k < blocks.contacts.size(); k++)
    if (k + 1 == blocks.contacts.size() || slab_of(blocks.contacts[k]) != slab_of(blocks.contacts[k + 1]))
      block_ends.push_back(k + 1);
  ASSERT_EQ(block_ends.size(), static_cast<std::size_t>(slabs));

  const cd::SolverSettings settings{1e-12, 100000, cd::ConvergenceNorm::quadratic};
  const cd::SolveReport in_blocks =
      testbed::solve_in_blocks(blocks.contacts, block_ends, blocks.bodies.velocity, settings);
  const cd::SolveReport in_order = cd::solve_gauss_seidel(plain.contacts, plain.bodies.velocity, settings);
  ASSERT_TRUE(in_blocks.converged);
  ASSERT_TRUE(in_order.converged);
  EXPECT_NE(in_blocks.iterations, in_order.iterations);
  const double fall = gravity * step.dt;
  for (const WalledStack* stack : {&blocks, &plain})
    for (std::size_t b = 1; b < stack->bodies.velocity.size(); b++) {
      EXPECT_NEAR(stack->bodies.velocity[b].vx, 0.0, 1e-9 * fall) << b;
      EXPECT_NEAR(stack->bodies.velocity[b].vy, 0.0, 1e-9 * fall) << b;
    }

  WalledStack single, reference;
  testbed::sweep_in_blocks(single.contacts, {single.contacts.size()}, single.bodies.velocity, {});
  cd::sweep(reference.contacts, reference.bodies.velocity, {});
  for (std::size_t b = 1; b < reference.bodies.velocity.size(); b++) {
    EXPECT_NEAR(single.bodies.velocity[b].vx, reference.bodies.velocity[b].vx, 1e-14 * fall) << b;
    EXPECT_NEAR(single.bodies.velocity[b].vy, reference.bodies.velocity[b].vy, 1e-14 * fall) << b;
  }
}

}  // namespace
