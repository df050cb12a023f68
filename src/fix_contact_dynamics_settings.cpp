// Reading fix contact/dynamics's command line into its settings
// (fix_contact_dynamics_settings.h).
#include "fix_contact_dynamics_settings.h"

#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "cd/solver_keywords.h"
#include "error.h"
#include "fix_contact_dynamics_keywords.h"

namespace LAMMPS_NS::fix_keywords {

namespace {

// Largest max_contacts: each atom carries 1 + 3 max_contacts doubles. A disk of radius R touches
// at most pi / asin(r / (R + r)) disks of radius r: about 300 at a size ratio R/r of 100.
constexpr int max_contacts_limit = 1000;

// One command line read into `settings`, keyword by keyword.
class SettingsParser {
 public:
  SettingsParser(int narg, char** arg, const double* boxlo, const double* boxhi, Error* error)
      : narg(narg), arg(arg), lo(boxlo), hi(boxhi), error(error)
  {
  }
  void parse_laws(int ntypes);
  void parse_keywords();
  void finish_step_grid();
  void check_step();

  FixSettings settings;
  cd::StepSettings step;

 private:
  void refuse_repeat(const std::string& keyword);
  int parse_order(int iarg);
  int parse_save_problems(int iarg);
  int parse_wall(int iarg);
  cd::ContactLaw parse_wall_law(int iarg);
  void parse_type_law(const char* keyword, int iarg, bool friction);
  void parse_value(const std::string& keyword, const char* value);

  const int narg;
  char** const arg;
  const double* const lo;  // the box
  const double* const hi;
  Error* const error;
  std::set<std::string> given;  // the keywords read so far
};

// mu and e for every type pair.
void SettingsParser::parse_laws(int ntypes)
{
  if (narg < 5)
    error->all(FLERR, "Fix contact/dynamics needs mu and e: fix ID group contact/dynamics mu e [keyword value ...]");
  const double mu = number_for("mu", arg[3], error);
  const double e = number_for("e", arg[4], error);
  check_friction("mu", mu, error);
  check_restitution("e", e, error);
  settings.law_types = ntypes;
  settings.type_laws.assign((ntypes + 1) * (ntypes + 1), cd::ContactLaw{mu, e});
}

void SettingsParser::parse_keywords()
{
  int iarg = 5;
  while (iarg < narg) {
    const std::string keyword = arg[iarg];
    refuse_repeat(keyword);
    if (keyword == "wall") {
      iarg = parse_wall(iarg);
    } else if (keyword == "mu/types" || keyword == "e/types") {
      parse_type_law(arg[iarg], iarg, keyword == "mu/types");
      iarg += 4;
    } else if (keyword == "order") {
      iarg = parse_order(iarg);
    } else if (keyword == "save_problems") {
      iarg = parse_save_problems(iarg);
    } else {
      require_values(arg[iarg], iarg, 1, narg, error);
      parse_value(keyword, arg[iarg + 1]);
      iarg += 2;
    }
  }
}

// A keyword of one setting given twice would silently keep its last value; walls and type laws
// add up.
void SettingsParser::refuse_repeat(const std::string& keyword)
{
  if (keyword == "wall" || keyword == "mu/types" || keyword == "e/types") return;
  if (!given.insert(keyword).second)
    error->all(FLERR, "Fix contact/dynamics: {} given twice; give each keyword once", keyword);
}

// order fixed | order shuffle seed
int SettingsParser::parse_order(int iarg)
{
  require_values("order", iarg, 1, narg, error, "fixed or shuffle seed");
  const std::string value = arg[iarg + 1];
  if (value == "fixed") {
    step.order = cd::ContactOrder::interleaved;
    return iarg + 2;
  }
  if (value != "shuffle") error->all(FLERR, "Fix contact/dynamics: order must be fixed or shuffle, got '{}'", value);
  require_values("order shuffle", iarg + 1, 1, narg, error, "seed");
  const int seed = integer_for("order shuffle seed", arg[iarg + 2], error);
  if (seed <= 0) error->all(FLERR, "Fix contact/dynamics: order shuffle seed must be > 0, got {}", seed);
  step.order = cd::ContactOrder::shuffled;
  settings.shuffle_seed = static_cast<std::uint64_t>(seed);
  return iarg + 3;
}

// save_problems sweeps prefix
int SettingsParser::parse_save_problems(int iarg)
{
  require_values("save_problems", iarg, 2, narg, error, "sweeps prefix");
  settings.save_problems_over = integer_for("save_problems", arg[iarg + 1], error);
  if (settings.save_problems_over < 0)
    error->all(FLERR, "Fix contact/dynamics: save_problems sweeps must be >= 0, got {}", settings.save_problems_over);
  settings.save_problems_prefix = arg[iarg + 2];
  return iarg + 3;
}

// The keywords of one value: the solver's read by the core (cd::read_solver_keyword), the rest
// here. The step's settings are range-checked by the core (check_step).
void SettingsParser::parse_value(const std::string& keyword, const char* value)
{
  if (const std::optional<std::string> solver_keyword = cd::read_solver_keyword(step.solver, keyword, value)) {
    if (!solver_keyword->empty()) error->all(FLERR, "Fix contact/dynamics: {}", *solver_keyword);
  } else if (keyword == "theta") {
    step.theta = number_for("theta", value, error);
  } else if (keyword == "join") {
    const std::string joining = value;
    if (joining == "during") step.joining = cd::Joining::during_solve;
    else if (joining == "after") step.joining = cd::Joining::after_solve;
    else error->all(FLERR, "Fix contact/dynamics: join must be during or after, got '{}'", joining);
  } else if (keyword == "warm_start") {
    step.warm_start = yes_or_no("warm_start", value, error);
  } else if (keyword == "pair_forces") {
    settings.pair_forces = yes_or_no("pair_forces", value, error);
  } else if (keyword == "max_contacts") {
    settings.max_contacts = integer_for("max_contacts", value, error);
    if (settings.max_contacts < 1 || settings.max_contacts > max_contacts_limit)
      error->all(FLERR, "Fix contact/dynamics: max_contacts must be in [1,{}], got {}", max_contacts_limit,
                 settings.max_contacts);
  } else if (keyword == "alert") {
    step.alert = number_for("alert", value, error);
  } else if (keyword == "dt_max") {
    settings.step_grid.dt_max = number_for("dt_max", value, error);
    if (settings.step_grid.dt_max <= 0.0)
      error->all(FLERR, "Fix contact/dynamics: dt_max must be > 0, got {}", settings.step_grid.dt_max);
  } else if (keyword == "dt_align") {
    settings.dt_align = number_for("dt_align", value, error);
    if (settings.dt_align <= 0.0)
      error->all(FLERR, "Fix contact/dynamics: dt_align must be > 0, got {}", settings.dt_align);
  } else if (keyword == "travel") {
    settings.travel_fraction = number_for("travel", value, error);
    if (settings.travel_fraction <= 0.0 || settings.travel_fraction > 0.5)
      error->all(FLERR, "Fix contact/dynamics: travel must be in (0,0.5] (a fraction of the neighbour skin), got {}",
                 settings.travel_fraction);
  } else if (keyword == "density") {
    settings.disc_density = number_for("density", value, error);
    if (settings.disc_density <= 0.0)
      error->all(FLERR, "Fix contact/dynamics: density must be > 0, got {}", settings.disc_density);
  } else {
    error->all(FLERR, "Fix contact/dynamics: unknown keyword '{}'", keyword);
  }
}

// mu/types I J mu | e/types I J e: the law of the type pairs in the ranges, both ways round.
void SettingsParser::parse_type_law(const char* keyword, int iarg, bool friction)
{
  const int ntypes = settings.law_types;
  require_values(keyword, iarg, 3, narg, error, friction ? "I J mu" : "I J e");
  const auto [ilo, ihi] = type_range_for(keyword, arg[iarg + 1], ntypes, error);
  const auto [jlo, jhi] = type_range_for(keyword, arg[iarg + 2], ntypes, error);
  const double value = number_for(keyword, arg[iarg + 3], error);
  if (friction) check_friction(keyword, value, error);
  else check_restitution(keyword, value, error);
  for (int i = ilo; i <= ihi; i++)
    for (int j = jlo; j <= jhi; j++) {
      cd::ContactLaw& ij = settings.type_laws[i * (ntypes + 1) + j];
      cd::ContactLaw& ji = settings.type_laws[j * (ntypes + 1) + i];
      (friction ? ij.mu : ij.restitution) = value;
      (friction ? ji.mu : ji.restitution) = value;
    }
}

// The friction and restitution of a wall, at arg[iarg] and arg[iarg + 1].
cd::ContactLaw SettingsParser::parse_wall_law(int iarg)
{
  const cd::ContactLaw law{number_for("wall mu", arg[iarg], error), number_for("wall e", arg[iarg + 1], error)};
  check_friction("wall mu", law.mu, error);
  check_restitution("wall e", law.restitution, error);
  return law;
}

// wall xplane X mu e | wall yplane Y mu e | wall segment x1 y1 x2 y2 mu e | wall region ID mu e
int SettingsParser::parse_wall(int iarg)
{
  if (iarg + 1 >= narg)
    error->all(FLERR,
               "Fix contact/dynamics: wall needs a shape and its values: xplane position mu e, yplane position mu "
               "e, segment x1 y1 x2 y2 mu e or region ID mu e");
  const std::string shape = arg[iarg + 1];
  const int number = static_cast<int>(settings.walls.size() + settings.region_walls.size()) + 1;
  if (shape == "region") {
    require_values("wall region", iarg + 1, 3, narg, error, "ID mu e");
    settings.region_walls.push_back({arg[iarg + 2], parse_wall_law(iarg + 3), number});
    return iarg + 5;
  }
  cd::Wall wall;
  int next;
  if (shape == "xplane" || shape == "yplane") {
    require_values(("wall " + shape).c_str(), iarg + 1, 3, narg, error, "position mu e");
    const int axis = shape == "xplane" ? 0 : 1;
    const double position = number_for(("wall " + shape).c_str(), arg[iarg + 2], error);
    if (position < lo[axis] || position > hi[axis])
      error->all(FLERR, "Fix contact/dynamics: wall {} at {} is outside the box [{}, {}]", shape, position, lo[axis],
                 hi[axis]);
    wall.shape = cd::Wall::Shape::line;
    if (axis == 0) wall.ax = wall.bx = position, wall.ay = lo[1], wall.by = hi[1];
    else wall.ay = wall.by = position, wall.ax = lo[0], wall.bx = hi[0];
    next = iarg + 3;
  } else if (shape == "segment") {
    require_values("wall segment", iarg + 1, 6, narg, error, "x1 y1 x2 y2 mu e");
    wall.shape = cd::Wall::Shape::segment;
    wall.ax = number_for("wall segment", arg[iarg + 2], error);
    wall.ay = number_for("wall segment", arg[iarg + 3], error);
    wall.bx = number_for("wall segment", arg[iarg + 4], error);
    wall.by = number_for("wall segment", arg[iarg + 5], error);
    const double xs[2] = {wall.ax, wall.bx}, ys[2] = {wall.ay, wall.by};
    for (int k = 0; k < 2; k++)
      if (xs[k] < lo[0] || xs[k] > hi[0] || ys[k] < lo[1] || ys[k] > hi[1])
        error->all(FLERR, "Fix contact/dynamics: wall segment end ({}, {}) is outside the box", xs[k], ys[k]);
    if (wall.ax == wall.bx && wall.ay == wall.by)
      error->all(FLERR, "Fix contact/dynamics: wall segment has zero length");
    next = iarg + 6;
  } else {
    error->all(FLERR, "Fix contact/dynamics: wall must be xplane, yplane, segment or region, got '{}'", shape);
  }
  wall.law = parse_wall_law(next);
  settings.walls.push_back(wall);
  settings.wall_numbers.push_back(number);
  return next + 2;
}

// dt_align and travel need dt_max; dt_align must be a whole multiple of it: the alignment period
// in steps.
void SettingsParser::finish_step_grid()
{
  const double dt_align = settings.dt_align;
  cd::StepGrid& grid = settings.step_grid;
  for (const char* keyword : {"dt_align", "travel"})
    if (given.count(keyword) && !settings.adaptive_step())
      error->all(FLERR, "Fix contact/dynamics: {} needs dt_max (the adaptive step)", keyword);
  if (!settings.adaptive_step()) return;
  const double periods = (dt_align > 0.0 ? dt_align : grid.dt_max) / grid.dt_max;
  if (periods < 0.5 || std::fabs(periods - std::round(periods)) > 1e-6 * periods)
    error->all(FLERR, "Fix contact/dynamics: dt_align {} must be a whole multiple of dt_max {}", dt_align, grid.dt_max);
  grid.steps_per_align = static_cast<int>(std::lround(periods));
}

// The core's ranges (cd::check), in the fix's error line.
void SettingsParser::check_step()
{
  const std::string problem = cd::check(step);
  if (!problem.empty()) error->all(FLERR, "Fix contact/dynamics: {}", problem);
}

}  // namespace

FixCommand parse_settings(int narg, char** arg, int ntypes, const double* boxlo, const double* boxhi, Error* error)
{
  SettingsParser parser(narg, arg, boxlo, boxhi, error);
  parser.parse_laws(ntypes);
  parser.parse_keywords();
  parser.finish_step_grid();
  parser.check_step();
  return {parser.settings, parser.step};
}

}  // namespace LAMMPS_NS::fix_keywords
