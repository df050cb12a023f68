// Decks and file readers shared by several LAMMPS-level tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fmt/format.h"

namespace cdtest {

// Two disks of diameter d in a periodic square box of side 10 d, touching through the
// boundary x = 0 = L, disk 1 (at x = L - r) moving at +v toward disk 2 (at x = r), at rest.
// `before_box` goes before the box is created (e.g. a processors command).
inline std::string periodic_impact_deck(double d, double v, double e, const std::string& before_box = "")
{
  const double L = 10 * d, r = 0.5 * d;
  return before_box + fmt::format(R"(
boundary p p p
region box block 0 {L} 0 {L} -{r} {r}
create_box 1 box
create_atoms 1 single {xa} {y} 0
create_atoms 1 single {xb} {y} 0
set group all diameter {d} density/disc 2500
velocity all set {v} 0 0 sum no units box
set atom 2 vx 0
neighbor {skin} bin
timestep 1e-5
fix cd all contact/dynamics 0.3 {e} tolerance 1e-12
fix 2d all enforce2d
run 1
)",
                                  fmt::arg("L", L), fmt::arg("r", r), fmt::arg("xa", L - r), fmt::arg("xb", r),
                                  fmt::arg("y", 0.5 * L), fmt::arg("d", d), fmt::arg("v", v), fmt::arg("skin", 0.2 * d),
                                  fmt::arg("e", e));
}

// The second column of a fix ave/time file, for the steps after `step` (the setup line of a
// run repeats its first step).
inline std::vector<double> ave_time_values_after(const std::string& path, double step)
{
  std::ifstream in(path);
  std::vector<double> values;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double at, value;
    fields >> at >> value;
    if (at > step) values.push_back(value);
  }
  return values;
}

}  // namespace cdtest
