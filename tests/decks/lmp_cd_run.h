// Runs lmp_cd on a deck written to a file and collects what it printed.
#pragma once

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#ifndef LMP_CD_EXECUTABLE
#error "LMP_CD_EXECUTABLE must name the lmp_cd executable"
#endif

namespace cdtest {

struct RunResult {
  int exit_status;  // as pclose returns it: 0 for a clean exit
  std::string output;
};

// `launcher` goes before the executable (e.g. "mpirun -np 2 ").
inline RunResult run_deck(const std::string& name, const std::string& deck, const std::string& launcher = "")
{
  const std::string path = "deck_" + name + ".in";
  std::ofstream(path) << deck;
  const std::string command = launcher + LMP_CD_EXECUTABLE " -log none -in " + path + " 2>&1";
  RunResult result{0, ""};
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  result.exit_status = pclose(pipe);
  std::remove(path.c_str());
  return result;
}

// The ERROR line LAMMPS printed, or "" if none.
inline std::string error_line(const std::string& output)
{
  const std::size_t start = output.find("ERROR");
  if (start == std::string::npos) return "";
  return output.substr(start, output.find('\n', start) - start);
}

// Two resting disks of 0.5 mm on the floor of a 20 d x-periodic cell with 2 atom types,
// everything the fix requires set; the fix and the run are the caller's.
inline const std::string two_grains = R"(
units si
dimension 2
atom_style sphere
atom_modify map array
comm_modify vel yes
neigh_modify delay 0
boundary p f p
region box block 0 0.01 0 0.01 -0.0003 0.0003
create_box 2 box
create_atoms 1 single 0.005 0.00025 0
create_atoms 1 single 0.006 0.00025 0
set group all diameter 5e-4 density/disc 2500
neighbor 1e-4 bin
timestep 1e-5
)";

}  // namespace cdtest
