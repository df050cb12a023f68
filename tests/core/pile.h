// A small pile of disks on a floor, solved by the core tests: impacts, resting and separating
// contacts together.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "cd/detection.h"
#include "cd/gauss_seidel.h"

namespace {

constexpr double radius = 0.5;    // m, mean
constexpr double density = 1.0;   // kg/m^2
constexpr double gravity = 9.81;  // m/s^2
const cd::StepParameters step{1e-3, 0.5};

// A pile of disks on a hexagonal lattice of spacing 2 radius on the floor y = 0, radii a little
// below radius (small gaps), random velocities and spins: impacts, resting and separating
// contacts together.
struct Pile {
  std::vector<cd::Disk> disks;  // body 1 + k is disks[k]
  cd::BodySet bodies;
  std::vector<cd::Contact> contacts;
};

Pile make_pile(double grain_mu, double floor_mu)
{
  constexpr int columns = 8, rows = 6;
  const cd::ContactLaw grain_law{grain_mu, 0.5}, floor_law{floor_mu, 0.5};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> shrink(0.0, 1e-3), speed(-0.05, 0.05), spin(-1.0, 1.0);

  Pile pile;
  std::vector<cd::Disk>& disks = pile.disks;
  for (int row = 0; row < rows; row++)
    for (int column = 0; column < columns - row % 2; column++)
      disks.push_back(
          {(2 * column + row % 2 + 1) * radius, (1.0 + row * std::sqrt(3.0)) * radius, radius * (1.0 - shrink(rng))});
  const int count = static_cast<int>(disks.size());
  pile.bodies.reset(count + 1);
  for (int k = 0; k < count; k++) {
    const double mass = M_PI * disks[k].radius * disks[k].radius * density;
    pile.bodies.inertia[1 + k] = {1.0 / mass, 1.0 / (0.5 * mass * disks[k].radius * disks[k].radius)};
    pile.bodies.start_velocity[1 + k] = {speed(rng), speed(rng) - 0.05, spin(rng)};
    pile.bodies.velocity[1 + k] = pile.bodies.start_velocity[1 + k];
    pile.bodies.velocity[1 + k].vy -= gravity * step.dt;
  }

  // The step's own selection (cd::StepContacts::offer): candidates within 0.01 radius, prepared.
  cd::StepContacts selected;
  selected.begin(pile.bodies, step, 0.01 * radius, false);
  for (int i = 0; i < count; i++) {
    if (disks[i].y < 1.5 * radius)
      selected.offer(cd::disk_world_geometry(1 + i, disks[i], 0.0, disks[i].y, 0.0, 1.0), floor_law, {i, -1}, {});
    for (int j = i + 1; j < count; j++)
      if (std::hypot(disks[i].x - disks[j].x, disks[i].y - disks[j].y) < 2.5 * radius)
        selected.offer(cd::disk_disk_geometry(1 + i, disks[i], 1 + j, disks[j]), grain_law, {i, j}, {});
  }
  pile.contacts = selected.solved;
  return pile;
}

}  // namespace
