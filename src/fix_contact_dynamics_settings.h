// The settings of fix contact/dynamics as its command line gives them, and the parser that
// reads them (fix ID group contact/dynamics mu e keyword value ...). Bad input stops the run
// with one error line naming the keyword (LAMMPS's Error::all).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cd/step.h"
#include "cd/time_step.h"
#include "cd/walls.h"
#include "fix_contact_dynamics_region_walls.h"

namespace LAMMPS_NS {
class Error;

namespace fix_keywords {

// The fix's own settings; the step's (theta, the solver's, warm_start, order, join) belong to
// its cd::MoreauJeanStep (FixCommand).
struct FixSettings {
  std::uint64_t shuffle_seed = 0;  // order shuffle's seed (> 0); 0 with the fixed order
  int max_contacts = 12;           // contacts carried per atom in the warm-start store
  double disc_density = 0.0;       // kg/m^2; > 0: masses reset to pi r^2 rho
  bool pair_forces = false;        // a pair style may act on the group's pairs too
  int law_types = 0;               // atom types when the fix was defined
  // mu and e of every type pair, (law_types+1)^2 row-major (law()): mu e, then mu/types, e/types.
  std::vector<cd::ContactLaw> type_laws;
  std::vector<cd::Wall> walls;                  // lines and segments, in the order given
  std::vector<int> wall_numbers;                // theirs among all walls (1-based)
  std::vector<RegionWallSetting> region_walls;  // regions, in the order given
  // The step that follows the flow (dt_max given): dt_max (s) and the alignment period in
  // steps of dt_max (dt_align / dt_max); its travel is set by the fix from the neighbour skin.
  cd::StepGrid step_grid;
  double dt_align = 0.0;         // s; 0: dt_max
  double travel_fraction = 0.4;  // largest travel of a grain in one step, in neighbour skins
  // save_problems: every step whose solve takes more than this many sweeps, or meets the cap,
  // written as <prefix>.<step>.cdp (cd/problem_file.h); -1: none.
  int save_problems_over = -1;
  std::string save_problems_prefix;

  bool adaptive_step() const { return step_grid.dt_max > 0.0; }
  const cd::ContactLaw& law(int itype, int jtype) const { return type_laws[itype * (law_types + 1) + jtype]; }
};

// A command line read: the fix's settings, and the step's, checked by the core (cd::check), which
// the fix hands to its step.
struct FixCommand {
  FixSettings fix;
  cd::StepSettings step;  // its alert: the alert keyword's, if given
};

// Reads arg[3..narg) (mu, e, then keywords). ntypes: the atom types (mu/types, e/types ranges);
// boxlo, boxhi: the box the walls must lie in.
FixCommand parse_settings(int narg, char** arg, int ntypes, const double* boxlo, const double* boxhi, Error* error);

}  // namespace fix_keywords
}  // namespace LAMMPS_NS
