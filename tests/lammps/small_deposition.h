// A small random rain of polydisperse disks on a floor, shared by the deck-level tests.
#pragma once

#include <string>

#include "fmt/format.h"

namespace cdtest {

constexpr double deposition_d = 5e-4;  // mean diameter (m)

// 20 d wide x-periodic cell, 12 x 12 disks dropped from a loose lattice with random sideways
// velocities; diameters uniform in [0.8, 1.2] d. `fix_options` is appended to the fix line;
// mu and e apply to grains and floor alike.
inline std::string small_deposition(int seed, const std::string& fix_options, double mu = 0.5, double e = 0.5)
{
  const double d = deposition_d;
  return fmt::format(R"(
boundary p f p
region box block 0 {L} 0 {H} -{r} {r}
create_box 1 box
lattice sq {spacing}
region fill block {lo} {hi} {bottom} {top} -{r} {r} units box
create_atoms 1 region fill
variable diameter atom {dmin}+{spread}*random(0,1,{seed})
variable sideways atom 0.05*normal(0,1,{seed2})
set group all diameter v_diameter
set group all density/disc 2500
set group all vx v_sideways
neighbor {skin} bin
timestep 1e-5
fix grav all gravity 9.81 vector 0 -1 0
fix cd all contact/dynamics {mu} {e} wall yplane 0.0 {mu} {e} {options}
fix 2d all enforce2d
)",
                     fmt::arg("L", 20 * d), fmt::arg("H", 40 * d), fmt::arg("r", 0.6 * d), fmt::arg("spacing", 1.5 * d),
                     fmt::arg("lo", 0.7 * d), fmt::arg("hi", 18.8 * d), fmt::arg("bottom", 2 * d),
                     fmt::arg("top", 19.9 * d), fmt::arg("dmin", 0.8 * d), fmt::arg("spread", 0.4 * d),
                     fmt::arg("seed", seed), fmt::arg("seed2", seed + 1), fmt::arg("skin", 0.2 * d),
                     fmt::arg("options", fix_options), fmt::arg("mu", mu), fmt::arg("e", e));
}

// What a deck re-specifies after read_restart of a small_deposition: the settings a restart
// file does not keep, the fixes, and `fix_options` on the fix line.
inline std::string small_deposition_after_restart(const std::string& fix_options)
{
  return fmt::format(R"(
neighbor {skin} bin
comm_modify vel yes
neigh_modify delay 0 every 1 check yes
fix grav all gravity 9.81 vector 0 -1 0
fix cd all contact/dynamics 0.5 0.5 wall yplane 0.0 0.5 0.5 {options}
fix 2d all enforce2d
)",
                     fmt::arg("skin", 0.2 * deposition_d), fmt::arg("options", fix_options));
}

}  // namespace cdtest
