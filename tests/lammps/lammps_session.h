// A LAMMPS instance with this project's styles, driven command by command from a test.
#pragma once

#include <string>
#include <vector>

#include "atom.h"
#include "fix.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"
#include "style_registry.h"

namespace cdtest {

// Lines common to every 2D deck: SI units, disks, and the atom map, ghost velocities and
// per-step neighbour checks the fix requires.
inline const char* disk_preamble = R"(
units si
dimension 2
atom_style sphere
atom_modify map array
comm_modify vel yes
neigh_modify delay 0 every 1 check yes
)";

class LammpsSession {
 public:
  explicit LammpsSession(MPI_Comm communicator = MPI_COMM_WORLD)
  {
    std::vector<const char*> args{"lmp", "-log", "none", "-screen", "none", "-nocite"};
    lmp = new LAMMPS_NS::LAMMPS(static_cast<int>(args.size()), const_cast<char**>(args.data()), communicator);
    LAMMPS_NS::register_project_styles(lmp);
  }
  ~LammpsSession() { delete lmp; }
  LammpsSession(const LammpsSession&) = delete;
  LammpsSession& operator=(const LammpsSession&) = delete;

  // Runs each line of `script` as a LAMMPS command.
  void commands(const std::string& script)
  {
    std::size_t start = 0;
    while (start < script.size()) {
      std::size_t end = script.find('\n', start);
      if (end == std::string::npos) end = script.size();
      const std::string line = script.substr(start, end - start);
      if (line.find_first_not_of(" \t") != std::string::npos) lmp->input->one(line);
      start = end + 1;
    }
  }

  int index_of(int atom_id) const { return lmp->atom->map(atom_id); }
  double x(int atom_id, int axis) const { return lmp->atom->x[index_of(atom_id)][axis]; }
  double v(int atom_id, int axis) const { return lmp->atom->v[index_of(atom_id)][axis]; }
  double spin(int atom_id) const { return lmp->atom->omega[index_of(atom_id)][2]; }

  LAMMPS_NS::Fix* fix(const std::string& id) const { return lmp->modify->fix[lmp->modify->find_fix(id)]; }

  LAMMPS_NS::LAMMPS* lmp;
};

}  // namespace cdtest
