// Contact kinematics of rigid disks: where two bodies touch, along which normal, with which gap.
#pragma once

#include "cd/kinematics.h"

namespace cd {

// Index of the static world body (walls): zero inverse mass, zero velocity, never updated.
inline constexpr int world_body = 0;

// The model's disks are uniform: m = pi r^2 rho for an areal density rho (kg/m^2), and
// I = m r^2 / 2. Every host takes masses and inertias from here.
inline constexpr double pi = 3.14159265358979323846;
inline constexpr double disk_inertia_factor = 0.5;
inline double disk_mass(double radius, double areal_density)
{
  return pi * radius * radius * areal_density;
}
inline BodyInertia disk_inertia(double mass, double radius)
{
  return {1.0 / mass, 1.0 / (disk_inertia_factor * mass * radius * radius)};
}

// Where and how two bodies meet, before any mechanics.
struct ContactGeometry {
  int body_a = 0;
  int body_b = 0;         // world_body for walls
  double normal_x = 0.0;  // unit normal pointing from b to a
  double normal_y = 0.0;
  double gap = 0.0;      // signed distance between surfaces, negative when overlapping (m)
  double lever_a = 0.0;  // distance from the centre of a to the contact point (m)
  double lever_b = 0.0;  // same for b; 0 for a wall point
  // Velocity of b's periodic image relative to body b (m/s): zero but across the sides of a
  // deforming box, whose images move with the box (Lees-Edwards shear).
  double image_vx = 0.0;
  double image_vy = 0.0;
};

// Geometry between disk a and disk b (b given at the periodic image nearest to a).
// Coincident centres have no defined normal: the caller must not pass them.
ContactGeometry disk_disk_geometry(int body_a, const Disk& a, int body_b, const Disk& b);

// Geometry between a disk and a fixed point of the world (the nearest point of a wall),
// given the vector (dx, dy) from that point to the disk centre, already reduced to the nearest
// periodic image, and the unit normal to use if the centre lies on the wall (dx = dy = 0).
ContactGeometry disk_world_geometry(int body_a, const Disk& a, double dx, double dy, double fallback_nx,
                                    double fallback_ny);

}  // namespace cd
