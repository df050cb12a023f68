#include "fix_contact_dynamics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "output.h"
#include "pair.h"
#include "update.h"
#include "utils.h"

#include "cd/impulse_row.h"
#include "cd/problem_file.h"

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

constexpr int output_columns = 7;
// Relative spread below which a mass/radius^k ratio counts as uniform over the group.
constexpr double uniform_ratio_tolerance = 1.0e-6;
// Overlaps deeper than this, in mean diameters, at the start of a run are reported.
constexpr double initial_overlap_warning = 0.01;
// Subdomains narrower than this many contact cutoffs are reported: there every grain is a
// ghost of a neighbouring rank, and a chute's flow measurably depended on the rank count
// (doc/benchmarks.md).
constexpr double narrow_subdomain_cutoffs = 2.0;

// Partners of wall contacts in the per-atom store are negative, atom IDs positive.
std::int64_t wall_partner(int wall_index, cd::WallPart part)
{
  return -(3 * std::int64_t{wall_index} + static_cast<int>(part) + 1);
}

// The 1-based wall number of a wall partner.
int wall_number(std::int64_t partner)
{
  return static_cast<int>((-partner - 1) / 3) + 1;
}

// A key's partner for messages: "atom ID" or "wall N".
std::string partner_name(std::int64_t partner)
{
  if (partner > 0) return fmt::format("atom {}", partner);
  return fmt::format("wall {}", wall_number(partner));
}

}  // namespace

/* ---------------------------------------------------------------------- */

FixContactDynamics::FixContactDynamics(LAMMPS* lmp, int narg, char** arg) : Fix(lmp, narg, arg)
{
  if (domain->dimension != 2) error->all(FLERR, "Fix contact/dynamics requires dimension 2");
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR, "Fix contact/dynamics requires atom_style sphere (per-atom radius, rmass, omega)");
  fix_keywords::FixCommand command =
      fix_keywords::parse_settings(narg, arg, atom->ntypes, domain->boxlo, domain->boxhi, error);
  settings = std::move(command.fix);
  contact_step = cd::MoreauJeanStep(command.step, settings.shuffle_seed);
  contact_step.keep_problems(settings.save_problems_over >= 0);
  if (settings.save_problems_over >= 0 && comm->nprocs > 1)
    error->all(FLERR, "Fix contact/dynamics: save_problems needs one rank (a saved problem is one rank's contacts)");

  time_integrate = 1;
  vector_flag = 1;
  size_vector = 16;
  global_freq = 1;
  extvector = 0;
  local_flag = 1;
  size_local_cols = output_columns;
  size_local_rows = 0;  // no contact until the first step is solved
  local_freq = 1;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  comm_forward = 3;        // vx, vy, spin of a body
  comm_reverse = 3;        // the change of a ghost's vx, vy, spin over one sweep
  virial_global_flag = 1;  // the contact stress, into compute pressure with fix_modify virial yes
  thermo_virial = 0;

  // With a varying step the clock is LAMMPS's time, not step x dt; step 0 is time 0 (this
  // version's reset_timestep keeps the time already run, e.g. a deposition before the chute).
  if (update->ntimestep == 0) set_clock(0.0);

  history_width = cd::impulse_row::width(settings.max_contacts);
  maxexchange = history_width + ObstacleMotion::values_per_atom;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) cd::impulse_row::clear(history[i]);
}

FixContactDynamics::~FixContactDynamics()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(history);
  memory->destroy(array_local);
}

int FixContactDynamics::setmask()
{
  int mask = INITIAL_INTEGRATE | FINAL_INTEGRATE | PRE_EXCHANGE;
  if (settings.disc_density > 0.0) mask |= PRE_FORCE;
  if (settings.adaptive_step()) mask |= END_OF_STEP;
  return mask;
}

/* ---------------------------------------------------------------------- */

void FixContactDynamics::init()
{
  distributed = comm->nprocs > 1;
  check_deforming_box();
  if (!comm->ghost_velocity)
    error->all(FLERR, "Fix contact/dynamics requires ghost velocities: use comm_modify vel yes");
  if (atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "Fix contact/dynamics requires an atom map: use atom_modify map hash");
  check_insertion_map();
  // The per-step displacement limit (half the skin) keeps every contact in the list only if
  // the list is rebuilt as soon as a grain has moved that far.
  if (neighbor->every != 1 || neighbor->delay != 0 || !neighbor->dist_check)
    error->all(FLERR,
               "Fix contact/dynamics requires neighbour lists checked every step: use "
               "neigh_modify delay 0 every 1 check yes");
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix contact/dynamics does not support run_style respa");
  if (atom->ntypes != settings.law_types)
    error->all(FLERR, "Fix contact/dynamics: the number of atom types changed since the fix was defined");
  check_integrators();
  check_pair_style();
  check_alert();

  // Largest radius now or announced by an insertion fix (fix pour, fix deposit).
  double rmax_local = 0.0;
  for (int i = 0; i < atom->nlocal; i++) rmax_local = std::max(rmax_local, atom->radius[i]);
  double rmax = 0.0;
  MPI_Allreduce(&rmax_local, &rmax, 1, MPI_DOUBLE, MPI_MAX, world);
  for (int f = 0; f < modify->nfix; f++)
    for (int itype = 1; itype <= atom->ntypes; itype++) {
      int query_type = itype;
      auto* radius = static_cast<double*>(modify->fix[f]->extract("radius", query_type));
      if (radius && query_type == 0) rmax = std::max(rmax, *radius);
    }
  if (rmax <= 0.0)
    error->all(FLERR, "Fix contact/dynamics: no grain radius known (no atoms and no fix pour or deposit)");
  covered_radius = rmax;
  const double cutoff = 2.0 * covered_radius + neighbor->skin;
  comm->cutghostuser = std::max(comm->cutghostuser, cutoff);
  request_neighbor_list();
  // Without a pair style LAMMPS knows no bin for atom sorting and switches it off (with a
  // warning); sorting keeps neighbours close in memory as grains flow. Half the contact cutoff,
  // LAMMPS's own default with a pair style, unless atom_modify sort set a bin.
  if (atom->sortfreq > 0 && atom->userbinsize == 0.0) atom->userbinsize = 0.5 * cutoff;
}

void FixContactDynamics::request_neighbor_list()
{
  const int irequest = neighbor->request(this, instance_me);
  NeighRequest* request = neighbor->requests[irequest];
  request->pair = 0;
  request->fix = 1;
  request->half = 1;
  request->size = 1;
  // Newton off: a pair across a periodic or processor boundary is listed from both sides and
  // kept once by atom ID, independent of the user's newton setting.
  request->newton = 2;
  request->cut = 1;
  request->cutoff = 2.0 * covered_radius + neighbor->skin;
}

void FixContactDynamics::init_list(int, NeighList* ptr)
{
  list = ptr;
}

// Pairs are looked at only among the neighbour list's, listed out to a gap of the skin at most:
// a larger alert would ask for pairs the list does not hold.
void FixContactDynamics::check_alert()
{
  if (settings.alert && *settings.alert > neighbor->skin)
    error->all(FLERR,
               "Fix contact/dynamics: alert {} is larger than the neighbour skin {}: pairs that far apart are "
               "not listed; lower alert or raise the skin (neighbor command)",
               *settings.alert, neighbor->skin);
}

// fix pour in this LAMMPS (29 Sep 2021) resizes the atom map after an insertion step only when
// the last grain it tried fitted: a step that places fewer grains than it asked for (a crowded
// insertion region) leaves an array map too short for the new atom IDs, and Atom::map_set
// writes past its end (a segmentation fault). A hash map grows by itself; `map yes` is an array
// below a million atom IDs.
void FixContactDynamics::check_insertion_map()
{
  if (atom->map_style == Atom::MAP_HASH) return;
  for (int f = 0; f < modify->nfix; f++)
    if (utils::strmatch(modify->fix[f]->style, "^pour"))
      error->all(FLERR,
                 "Fix contact/dynamics: fix {} (pour) crashes this LAMMPS with an array atom map (map array "
                 "or yes) when an insertion falls short; use atom_modify map hash",
                 modify->fix[f]->id);
}

void FixContactDynamics::check_integrators()
{
  const int* mask = atom->mask;
  for (int f = 0; f < modify->nfix; f++) {
    Fix* other = modify->fix[f];
    if (other == this || !other->time_integrate) continue;
    int shared_local = (other->igroup == igroup || other->igroup == 0 || igroup == 0) ? 1 : 0;
    for (int i = 0; i < atom->nlocal && !shared_local; i++)
      if ((mask[i] & groupbit) && (mask[i] & other->groupbit)) shared_local = 1;
    int shared = 0;
    MPI_Allreduce(&shared_local, &shared, 1, MPI_INT, MPI_MAX, world);
    if (shared)
      error->all(FLERR, "Fix contact/dynamics: fix {} ({}) also integrates atoms of group {}", other->id, other->style,
                 group->names[igroup]);
  }
}

// A pair style's forces between two grains of the group would act on top of the rigid
// contacts (springs added to contacts that never overlap): refused unless pair_forces yes says
// they are wanted (e.g. cohesion). Pair::init() has set cutsq for every type pair by now; a
// type pair with no interaction (pair_style none, hybrid none) has cutsq 0, pair_style zero
// exerts no force.
void FixContactDynamics::check_pair_style()
{
  Pair* pair = force->pair;
  if (settings.pair_forces || !pair || !pair->cutsq || utils::strmatch(force->pair_style, "^zero")) return;
  const int ntypes = atom->ntypes;
  std::vector<int> present_local(ntypes + 1, igroup == 0 ? 1 : 0), present(ntypes + 1, 0);
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) present_local[atom->type[i]] = 1;
  MPI_Allreduce(present_local.data(), present.data(), ntypes + 1, MPI_INT, MPI_MAX, world);
  for (int itype = 1; itype <= ntypes; itype++)
    for (int jtype = itype; jtype <= ntypes; jtype++)
      if (present[itype] && present[jtype] && pair->cutsq[itype][jtype] > 0.0)
        error->all(FLERR,
                   "Fix contact/dynamics: pair style {} also acts on atoms of group {} (types {} and {}); "
                   "remove it, or add pair_forces yes to keep its forces",
                   force->pair_style, group->names[igroup], itype, jtype);
}

// At setup and whenever the atom count changed (insertions): the masses checked, the mean
// diameter (the unit of the overlap outputs) and the default alert distance that follows it.
void FixContactDynamics::survey_group()
{
  check_disk_masses();
  mean_diameter = group_mean_diameter();
  contact_step.set_alert(settings.alert.value_or(cd::default_alert_diameters * mean_diameter));
  natoms_surveyed = atom->natoms;
  int obstacle_here = 0;
  for (int i = 0; i < atom->nlocal && !obstacle_here; i++) obstacle_here = (atom->mask[i] & groupbit) ? 0 : 1;
  int obstacle_anywhere = 0;
  MPI_Allreduce(&obstacle_here, &obstacle_anywhere, 1, MPI_INT, MPI_MAX, world);
  obstacles_present = obstacle_anywhere != 0;
}

// Disks need m = pi r^2 rho. Sphere masses (4/3 pi r^3 rho, as fix pour and set density give)
// show in a polydisperse group as a uniform mass/r^3 with a non-uniform mass/r^2.
void FixContactDynamics::check_disk_masses()
{
  double local[4];  // max m/r^2, max -m/r^2, max m/r^3, max -m/r^3
  for (double& value : local) value = -HUGE_VAL;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double r = atom->radius[i];
    if (r <= 0.0 || atom->rmass[i] <= 0.0)
      error->one(FLERR, "Fix contact/dynamics: atom {} has radius {} and mass {}; both must be > 0", atom->tag[i], r,
                 atom->rmass[i]);
    const double per_area = atom->rmass[i] / (r * r);
    const double per_volume = per_area / r;
    local[0] = std::max(local[0], per_area);
    local[1] = std::max(local[1], -per_area);
    local[2] = std::max(local[2], per_volume);
    local[3] = std::max(local[3], -per_volume);
  }
  double global[4];
  MPI_Allreduce(local, global, 4, MPI_DOUBLE, MPI_MAX, world);
  if (settings.disc_density > 0.0 || global[0] == -HUGE_VAL) return;  // masses set here, or no grain
  const bool area_uniform = global[0] <= -global[1] * (1.0 + uniform_ratio_tolerance);
  const bool volume_uniform = global[2] <= -global[3] * (1.0 + uniform_ratio_tolerance);
  if (!area_uniform && volume_uniform)
    error->all(FLERR,
               "Fix contact/dynamics: group {} has sphere masses (4/3 pi r^3 rho); use set "
               "density/disc or the density keyword",
               group->names[igroup]);
}

// Of the group's grains; before any exists (an insertion fix fills the box later), the largest
// announced one.
double FixContactDynamics::group_mean_diameter()
{
  double local[2] = {0.0, 0.0};  // sum of diameters, count
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) {
      local[0] += 2.0 * atom->radius[i];
      local[1] += 1.0;
    }
  double global[2];
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, world);
  return global[1] > 0.0 ? global[0] / global[1] : 2.0 * covered_radius;
}

void FixContactDynamics::assign_disc_masses()
{
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) atom->rmass[i] = cd::disk_mass(atom->radius[i], settings.disc_density);
}

void FixContactDynamics::setup(int)
{
  if (settings.disc_density > 0.0) assign_disc_masses();
  survey_group();
  check_subdomains();
  warn_initial_overlaps();
  obstacles.record_starts(*atom, groupbit);
  overlaps_measured_at = -1;
  run_statistics.clear();
  if (settings.adaptive_step()) init_step_grid();
}

/* ----------------------------------------------------------------------
   The step that follows the flow (cd::StepGrid): at the start of a run the level is taken
   from the grains' speeds unless a previous run or a restart left one, then revised each time
   an alignment period ends.
------------------------------------------------------------------------- */

void FixContactDynamics::init_step_grid()
{
  settings.step_grid.travel = settings.travel_fraction * neighbor->skin;
  if (!step_clock.known) {
    // Without the level and position a restart on this grid left, the grid starts afresh here:
    // only at a whole period, or the level changes would miss the sample times.
    const double time = current_time();
    if (!settings.step_grid.on_alignment(time))
      error->all(FLERR,
                 "Fix contact/dynamics: the step grid cannot start at time {:.10g} s, not a whole number of "
                 "alignment periods ({:.4g} s); continue from a restart written with the same dt_max and dt_align",
                 time, settings.step_grid.period());
    step_clock.start(fastest_grain_level());
  }
  set_timestep(settings.step_grid.step(step_clock.level));
}

void FixContactDynamics::end_of_step()
{
  if (!step_clock.advance(settings.step_grid)) return;
  step_clock.level = fastest_grain_level();
  set_timestep(settings.step_grid.step(step_clock.level));
}

// The level of the grid that keeps the fastest grain's travel per step within the bound; a
// grain too fast for the smallest step stops the run after a restart is written.
int FixContactDynamics::fastest_grain_level()
{
  struct {
    double speed;
    int tag;
  } local{0.0, 0}, fastest{0.0, 0};
  double** v = atom->v;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double speed = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1]);
    if (speed > local.speed) local = {speed, static_cast<int>(atom->tag[i])};
  }
  MPI_Allreduce(&local, &fastest, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  const int level = settings.step_grid.level_for(fastest.speed);
  if (level < 0) {
    output->write_restart(update->ntimestep);
    error->all(FLERR,
               "Fix contact/dynamics: atom {} moves at {:.4g} m/s; the smallest step {:.4g} (dt_max/2^{}) "
               "moves it {:.4g}, more than travel x skin = {:.4g} (restart files written if a restart command is set)",
               fastest.tag, fastest.speed, settings.step_grid.step(settings.step_grid.max_level),
               settings.step_grid.max_level, fastest.speed * settings.step_grid.step(settings.step_grid.max_level),
               settings.step_grid.travel);
  }
  return level;
}

// As fix dt/reset does: time so far at the old step, then the new step everywhere it is kept.
void FixContactDynamics::set_timestep(double dt)
{
  if (dt == update->dt) return;
  update->update_time();
  update->dt = dt;
  update->dt_default = 0;
  if (force->pair) force->pair->reset_dt();
  for (int f = 0; f < modify->nfix; f++) modify->fix[f]->reset_dt();
}

// A pair across a periodic or rank boundary is listed from both sides: the side with the
// smaller atom ID takes it (on the rank that owns that atom).
template <class Visit>
void FixContactDynamics::for_each_listed_pair(Visit&& visit) const
{
  const tagint* tag = atom->tag;
  const int nlocal = atom->nlocal;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int* neighbours = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = neighbours[jj] & NEIGHMASK;
      if (j >= nlocal && tag[i] > tag[j]) continue;
      visit(i, j);
    }
  }
}

template <class Visit>
void FixContactDynamics::for_each_grain_overlap(Visit&& visit) const
{
  double** x = atom->x;
  const double* radius = atom->radius;
  const int* mask = atom->mask;
  // Most listed pairs are apart: the squared distance tells them without a square root.
  for_each_listed_pair([&](int i, int j) {
    if (!(mask[i] & groupbit) && !(mask[j] & groupbit)) return;
    const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1];
    const double touching = radius[i] + radius[j];
    const double distance_sq = dx * dx + dy * dy;
    if (distance_sq < touching * touching) visit(touching - std::sqrt(distance_sq));
  });
  const cd::PeriodicBox box = periodic_box();
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (const cd::Wall& wall : settings.walls)
      if (const auto touch = cd::wall_contact(wall, 0, {x[i][0], x[i][1], radius[i]}, 0.0, box))
        if (touch->geometry.gap < 0.0) visit(-touch->geometry.gap);
  }
}

// Rigid contacts never push overlapping grains apart: grains created overlapping (random
// placement, a lattice that does not fit the periodic cell) stay so. Say it at the start.
void FixContactDynamics::warn_initial_overlaps()
{
  const double threshold = initial_overlap_warning * mean_diameter;
  double local[2] = {0.0, 0.0};  // count, deepest
  for_each_grain_overlap([&](double depth) {
    if (depth <= threshold) return;
    local[0] += 1.0;
    local[1] = std::max(local[1], depth);
  });
  double global[2];
  MPI_Allreduce(&local[0], &global[0], 1, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(&local[1], &global[1], 1, MPI_DOUBLE, MPI_MAX, world);
  if (global[0] > 0.0 && comm->me == 0)
    error->warning(FLERR,
                   "Fix contact/dynamics: {} contacts overlap by up to {:.3g} mean diameters "
                   "at the start of the run; rigid contacts keep such overlaps, create the grains "
                   "apart",
                   static_cast<bigint>(global[0]), global[1] / mean_diameter);
}

// A ghost must be one hop from its owner: the exchange sends each ghost's velocity change
// straight back to the rank that owns it.
void FixContactDynamics::check_subdomains()
{
  const double cutoff = 2.0 * covered_radius + neighbor->skin;
  if (!distributed) return;
  const double width = narrowest_split_subdomain();
  if (width < cutoff)
    error->all(FLERR,
               "Fix contact/dynamics: an MPI subdomain is thinner than the contact cutoff "
               "{} (2 max radius + skin); use fewer ranks or another processors grid",
               cutoff);
  if (width < narrow_subdomain_cutoffs * cutoff && !narrow_subdomains_reported) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "Fix contact/dynamics: MPI subdomains down to {:.3g} wide, less than {:g} "
                     "contact cutoffs ({:.3g}); the decomposed sweep slowed a chute on subdomains "
                     "this narrow, use fewer ranks along that axis",
                     width, narrow_subdomain_cutoffs, cutoff);
    narrow_subdomains_reported = true;
  }
}

// Width of the narrowest subdomain, over all ranks, along the axes split between ranks (an RCB
// tiling may split either). A triclinic box splits in reduced coordinates: a slice along x is
// bounded by lines along the tilted edge (xy, ly), a slice along y by lines along x.
double FixContactDynamics::narrowest_split_subdomain()
{
  double width[2];
  if (domain->triclinic) {
    width[0] = (domain->subhi_lamda[0] - domain->sublo_lamda[0]) * domain->xprd * domain->yprd /
               std::hypot(domain->yprd, domain->xy);
    width[1] = (domain->subhi_lamda[1] - domain->sublo_lamda[1]) * domain->yprd;
  } else {
    for (int axis = 0; axis < 2; axis++) width[axis] = domain->subhi[axis] - domain->sublo[axis];
  }
  double local = std::numeric_limits<double>::max();
  for (int axis = 0; axis < 2; axis++)
    if (comm->layout == Comm::LAYOUT_TILED || comm->procgrid[axis] > 1) local = std::min(local, width[axis]);
  double global = local;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MIN, world);
  return global;
}

void FixContactDynamics::pre_force(int)
{
  assign_disc_masses();
}

/* ----------------------------------------------------------------------
   Moreau–Jean step. initial_integrate moves the group to the predicted configuration
   x_m = x_n + (1-theta) dt v_n, where LAMMPS then finds neighbours and computes forces;
   final_integrate solves for v_{n+1} at x_m and completes x_{n+1} = x_m + theta dt v_{n+1}.
------------------------------------------------------------------------- */

void FixContactDynamics::initial_integrate(int vflag)
{
  v_init(vflag);
  const cd::StepParameters step = step_parameters();
  double** x = atom->x;
  double** v = atom->v;
  const int* mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) {
      const cd::Displacement shift = cd::predicted_motion({v[i][0], v[i][1], 0.0}, step);
      x[i][0] += shift.dx;
      x[i][1] += shift.dy;
    }
}

void FixContactDynamics::final_integrate()
{
  if (atom->natoms != natoms_surveyed) {
    if (settings.disc_density > 0.0) assign_disc_masses();
    survey_group();
  }
  if (neighbor->ago == 0) check_subdomains();
  place_obstacles();
  step_box = periodic_box().advanced(step_parameters().lead());
  if (domain_deforms) share_image_shifts();
  gather_bodies();
  RankExchange exchange(*this);
  LammpsHost host(*this);
  const cd::StepReport report = contact_step.solve(bodies, update->dt, host, distributed ? &exchange : nullptr);
  last_report = report.solve;
  save_hard_problem();  // heights at x_m, before the corrector moves the atoms
  loaded_contacts = report.loaded_contacts;
  store_impulses();
  tally_contact_stress();
  fill_local_output();
  write_back_motion();
  reduce_step_outputs();
  if (obstacles_present) obstacles.record_starts(*atom, groupbit);

  count_solve();
}

// The running totals and the run's statistics; a warning on the 1st, 10th, 100th ...
// unconverged step.
void FixContactDynamics::count_solve()
{
  run_statistics.record(last_report);
  total_iterations += last_report.iterations;
  total_steps += 1.0;
  if (last_report.converged) return;
  total_unconverged_steps += 1.0;
  const double count = total_unconverged_steps;
  if (comm->me == 0 && std::fabs(std::log10(count) - std::round(std::log10(count))) < 1e-12)
    error->warning(FLERR,
                   "Fix contact/dynamics: iteration cap {} reached at step {} (residual {:.3g}); "
                   "{} step(s) unconverged so far",
                   contact_step.settings().solver.max_iterations, update->ntimestep, last_report.residual, count);
}

// save_problems: the step's problem as the solver met it, with each body's height, if its solve
// took more sweeps than asked or met the cap (one rank: a problem is one rank's contacts).
void FixContactDynamics::save_hard_problem()
{
  if (settings.save_problems_over < 0) return;
  if (last_report.converged && last_report.iterations <= settings.save_problems_over) return;
  cd::ContactProblem problem = contact_step.kept_problem();
  problem.height.assign(problem.free_velocity.size(), 0.0);
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) problem.height[body_of_atom[i]] = atom->x[i][1];
  problem.label =
      fmt::format("step {} time {} dt {} sweeps {} converged {} final norm {}", update->ntimestep, current_time(),
                  update->dt, last_report.iterations, last_report.converged ? 1 : 0, last_report.residual);
  const std::string path = fmt::format("{}.{}.cdp", settings.save_problems_prefix, update->ntimestep);
  try {
    cd::write_problem(path, problem);
  } catch (const std::runtime_error& failure) {
    error->one(FLERR, "Fix contact/dynamics: save_problems: {}", failure.what());
  }
}

cd::StepParameters FixContactDynamics::step_parameters() const
{
  return {update->dt, contact_step.settings().theta};
}

// Obstacles that other fixes moved this step are met at the grains' instant x_m
// (ObstacleMotion); one moving more than half the skin could pass through a pair the
// neighbour list does not hold.
void FixContactDynamics::place_obstacles()
{
  obstacles.measure_travel(*atom, *domain, groupbit);
  if (!obstacles_present) return;
  const double step_limit = 0.5 * neighbor->skin;
  for (int i = 0; i < atom->nlocal; i++) {
    const cd::Displacement& s = obstacles.travel(i);
    if (std::hypot(s.dx, s.dy) > step_limit)
      error->one(FLERR,
                 "Fix contact/dynamics: obstacle atom {} moved {} in step {}, more than half the neighbour skin {}; "
                 "reduce the time step or raise the skin",
                 atom->tag[i], std::hypot(s.dx, s.dy), update->ntimestep, neighbor->skin);
  }
  forward_field = ForwardField::obstacle_travel;
  comm->forward_comm_fix(this, 2);
  forward_field = ForwardField::velocity;
}

cd::Disk FixContactDynamics::disk_at_solve(int i) const
{
  return obstacles.disk_at_solve(i, atom->x[i], atom->radius[i], contact_step.settings().theta);
}

/* ---------------------------------------------------------------------- */

// Bodies: 0 is the world, 1 + i an owned atom i, 1 + g a ghost g whose owner is on another
// rank. A periodic image of an owned atom is that atom's body; several images of one remote
// atom share the body of the image LAMMPS's atom map returns.
void FixContactDynamics::map_bodies()
{
  const int nall = atom->nlocal + atom->nghost;
  body_of_atom.resize(nall);
  for (int j = 0; j < nall; j++) {
    const int canonical = j < atom->nlocal ? j : atom->map(atom->tag[j]);
    if (canonical < 0)
      error->one(FLERR, "Fix contact/dynamics: ghost atom {} is missing from the atom map", atom->tag[j]);
    body_of_atom[j] = 1 + canonical;
  }
}

void FixContactDynamics::gather_bodies()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const double dt = update->dt;
  double** v = atom->v;
  double** f = atom->f;
  double** omega = atom->omega;
  double** torque = atom->torque_flag ? atom->torque : nullptr;
  const double* radius = atom->radius;
  const double* rmass = atom->rmass;
  const int* mask = atom->mask;

  map_bodies();
  bodies.reset(1 + nall);
  for (int i = 0; i < nall; i++) {
    if (body_of_atom[i] != 1 + i) continue;  // a periodic image of another body
    if (i < nlocal && radius[i] > covered_radius)
      error->one(FLERR,
                 "Fix contact/dynamics: atom {} has radius {}, larger than the {} the "
                 "neighbour cutoff was set for; start a new run",
                 atom->tag[i], radius[i], covered_radius);
    // LAMMPS gave a ghost its owner's velocity plus its image's: the body keeps its owner's.
    double image_vx = 0.0, image_vy = 0.0;
    image_velocity_of(i, image_vx, image_vy);
    const cd::BodyVelocity own{v[i][0] - image_vx, v[i][1] - image_vy, omega[i][2]};
    const bool grain = mask[i] & groupbit;
    // An obstacle: infinite mass, at the velocity of the step another fix moved it through.
    const cd::BodyVelocity start = grain ? own : obstacles.velocity(i, own, dt);
    bodies.start_velocity[1 + i] = start;
    bodies.velocity[1 + i] = start;
    if (!grain) continue;
    // Ghost masses are refreshed only at reneighbouring: take them from the density if set.
    const double mass = settings.disc_density > 0.0 ? cd::disk_mass(radius[i], settings.disc_density) : rmass[i];
    const cd::BodyInertia& inertia = bodies.inertia[1 + i] = cd::disk_inertia(mass, radius[i]);
    if (i >= nlocal) continue;  // ghosts receive their owner's free velocity below
    bodies.velocity[1 + i] = cd::free_velocity(start, inertia, f[i][0], f[i][1], torque ? torque[i][2] : 0.0, dt);
  }
  if (distributed) {
    ghost_reference.resize(bodies.velocity.size());
    comm->forward_comm_fix(this);
  }
}

// The listed pairs whose gap lies above their reach plus from_margin and at most their reach
// plus to_margin (cd::PairReach), and the walls likewise, offered to the step's contacts.
void FixContactDynamics::LammpsHost::collect_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                                   cd::StepContacts& contacts)
{
  fix.collect_grain_pairs(reach, from_margin, to_margin, contacts);
  fix.collect_wall_pairs(reach, from_margin, to_margin, contacts);
}

void FixContactDynamics::collect_grain_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                             cd::StepContacts& contacts)
{
  const int* type = atom->type;
  const int* mask = atom->mask;
  // An image across a side of a deforming box moves at its body's velocity plus the box's (j is
  // the ghost; i is owned): LAMMPS placed it with the box at the start of the step, the step
  // meets it at the predicted configuration, and its look reaches as far as its speed.
  const double predictor = step_parameters().lead();
  const double advance = step_parameters().advance();
  // Positions as they are unless obstacles may have moved or the box deforms (no lookups).
  const bool displaced = obstacles_present || domain_deforms;
  double** x = atom->x;
  const double* radius = atom->radius;
  for_each_listed_pair([&](int i, int j) {
    if (!(mask[i] & groupbit) && !(mask[j] & groupbit)) return;
    const int body_j = body_of_atom[j];
    double image_vx = 0.0, image_vy = 0.0, image_reach = 0.0;
    cd::Disk disk_i{x[i][0], x[i][1], radius[i]}, disk_j{x[j][0], x[j][1], radius[j]};
    if (displaced) {
      image_velocity_of(j, image_vx, image_vy);
      image_reach = advance * std::sqrt(image_vx * image_vx + image_vy * image_vy);
      disk_i = disk_at_solve(i);
      disk_j = disk_at_solve(j);
      disk_j.x += predictor * image_vx;
      disk_j.y += predictor * image_vy;
    }
    if (!reach.in_look(1 + i, disk_i, body_j, disk_j, from_margin + image_reach, to_margin + image_reach)) return;
    if (body_j == 1 + i)
      error->one(FLERR, "Fix contact/dynamics: atom {} touches its own periodic image; the cell is too short",
                 atom->tag[i]);
    const cd::PairKey key = pair_key(i, j);
    cd::ContactGeometry geometry = cd::disk_disk_geometry(1 + i, disk_i, body_j, disk_j);
    geometry.image_vx = image_vx;
    geometry.image_vy = image_vy;
    contacts.offer(geometry, settings.law(type[i], type[j]), key, carried_impulse(key));
  });
}

// The warm start of a pair lives with its smaller atom ID, which the rule of
// collect_grain_pairs makes an owned atom, keyed by the other ID.
cd::PairKey FixContactDynamics::pair_key(int i, int j) const
{
  const tagint* tag = atom->tag;
  if (tag[i] < tag[j]) return {i, tag[j]};
  return {j, tag[i]};
}

cd::PeriodicBox FixContactDynamics::periodic_box() const
{
  const double* rate = domain->h_rate;  // Voigt: xx, yy, zz, yz, xz, xy
  return {domain->xperiodic != 0,
          domain->yperiodic != 0,
          domain->xprd,
          domain->yprd,
          domain->triclinic ? domain->xy : 0.0,
          rate[0],
          rate[1],
          rate[5]};
}

void FixContactDynamics::collect_wall_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                            cd::StepContacts& contacts)
{
  if (settings.walls.empty()) return;
  // A wall's images move with a deforming box, one edge vector at the speeds below at most.
  const double image_reach = step_parameters().advance() *
                             (std::fabs(step_box.rate_x) + std::fabs(step_box.rate_y) + std::fabs(step_box.rate_xy));
  from_margin += image_reach;
  to_margin += image_reach;
  double** x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const cd::Disk disk{x[i][0], x[i][1], atom->radius[i]};
    const double reach_i = reach.reach(1 + i);
    for (int w = 0; w < static_cast<int>(settings.walls.size()); w++) {
      const auto touch = cd::wall_contact(settings.walls[w], 1 + i, disk, reach_i + to_margin, step_box);
      if (!touch || !reach.wall_in_look(1 + i, touch->geometry.gap, from_margin)) continue;
      const cd::PairKey key{i, wall_partner(w, touch->part)};
      contacts.offer(touch->geometry, settings.walls[w].law, key, carried_impulse(key));
    }
  }
}

/* ----------------------------------------------------------------------
   Warm start: the atom with the smaller ID of a pair (or the atom touching a wall) stores the
   impulses of its loaded contacts, keyed by partner atom ID (or wall slot). Seen from either
   body the pair has the same (p_n, p_t): swapping a and b flips both normal and tangent.
------------------------------------------------------------------------- */

cd::Local2 FixContactDynamics::carried_impulse(const cd::PairKey& key) const
{
  return cd::impulse_row::find(history[key.row], key.partner);
}

// The step's loaded contacts replace what the owned atoms carried.
void FixContactDynamics::store_impulses()
{
  for (int i = 0; i < atom->nlocal; i++) cd::impulse_row::clear(history[i]);
  contact_step.contacts().for_each_loaded([&](const cd::PairKey& key, const cd::Contact& contact) {
    const cd::Local2 p = contact.impulse;
    if (!std::isfinite(p.n) || !std::isfinite(p.t))
      error->one(FLERR, "Fix contact/dynamics: non-finite impulse between atom {} and {} at step {}",
                 atom->tag[key.row], partner_name(key.partner), update->ntimestep);
    if (!cd::impulse_row::append(history[key.row], settings.max_contacts, key.partner, p))
      error->one(FLERR, "Fix contact/dynamics: atom {} has more than {} loaded contacts; raise max_contacts",
                 atom->tag[key.row], settings.max_contacts);
  });
}

void FixContactDynamics::write_back_motion()
{
  const cd::StepParameters step = step_parameters();
  // Neighbour lists are rebuilt once a grain has moved half the skin; a grain moving more than
  // that in one step could pass through a pair the list does not hold.
  const double step_limit_sq = 0.25 * neighbor->skin * neighbor->skin;
  double** x = atom->x;
  double** v = atom->v;
  double** omega = atom->omega;
  const int* mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const cd::BodyVelocity& velocity = bodies.velocity[1 + i];
    if (!std::isfinite(velocity.vx) || !std::isfinite(velocity.vy) || !std::isfinite(velocity.spin))
      error->one(FLERR, "Fix contact/dynamics: non-finite velocity of atom {} at step {}", atom->tag[i],
                 update->ntimestep);
    const cd::Displacement moved = cd::step_motion(bodies.start_velocity[1 + i], velocity, step);
    if (moved.dx * moved.dx + moved.dy * moved.dy > step_limit_sq)
      error->one(FLERR,
                 "Fix contact/dynamics: atom {} moved {} in step {}, more than half the "
                 "neighbour skin {}; reduce the time step or raise the skin",
                 atom->tag[i], std::hypot(moved.dx, moved.dy), update->ntimestep, neighbor->skin);
    v[i][0] = velocity.vx;
    v[i][1] = velocity.vy;
    omega[i][2] = velocity.spin;
    const cd::Displacement shift = cd::corrected_motion(velocity, step);
    x[i][0] += shift.dx;
    x[i][1] += shift.dy;
  }
}

// The step's output vector: sums over ranks.
void FixContactDynamics::reduce_step_outputs()
{
  const double local_sums[3] = {static_cast<double>(contact_step.contacts().solved.size()),
                                static_cast<double>(loaded_contacts), last_report.contact_updates};
  double sums[3];
  MPI_Allreduce(local_sums, sums, 3, MPI_DOUBLE, MPI_SUM, world);
  solved_contacts_total = sums[0];
  loaded_contacts_total = sums[1];
  full_sweep_work = sums[0] > 0.0 ? sums[2] / sums[0] : 0.0;
}

// Outputs 5 and 6 from the positions when they are read, after every fix has moved its atoms
// (the corrector, fix move, ...): what a user measures at the end of the step. The ghosts are
// brought to their owners' positions first. Called on every rank (LAMMPS evaluates global
// outputs on all), once a step.
void FixContactDynamics::measure_overlaps()
{
  comm->forward_comm();
  double local[2] = {0.0, 0.0};  // deepest, sum (m)
  for_each_grain_overlap([&](double depth) {
    local[0] = std::max(local[0], depth);
    local[1] += depth;
  });
  double deepest = 0.0, total = 0.0;
  MPI_Allreduce(&local[0], &deepest, 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(&local[1], &total, 1, MPI_DOUBLE, MPI_SUM, world);
  max_overlap = deepest / mean_diameter;
  mean_overlap = solved_contacts_total > 0.0 ? total / solved_contacts_total / mean_diameter : 0.0;
  overlaps_measured_at = update->ntimestep;
}

// Between runs outputs are read without the run's lists: measure the last step's now.
void FixContactDynamics::post_run()
{
  if (mean_diameter > 0.0 && overlaps_measured_at != update->ntimestep) measure_overlaps();
  if (comm->me == 0)
    utils::logmesg(lmp, "Fix contact/dynamics {} solver: {}\n", id, cd::describe(run_statistics.summary()));
}

/* ----------------------------------------------------------------------
   Exchange across ranks. A sweep changes the velocities of owned bodies and of ghost bodies
   touched by contacts this rank solves; the changes of ghosts are summed into their owners,
   then every ghost takes its owner's velocity again.
------------------------------------------------------------------------- */

void FixContactDynamics::RankExchange::share_velocities()
{
  fix.comm->reverse_comm_fix(&fix);
  fix.comm->forward_comm_fix(&fix);
}

void FixContactDynamics::RankExchange::sum_over_ranks(double* values, int count)
{
  MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_SUM, fix.world);
}

void FixContactDynamics::RankExchange::after_sweep(cd::SweepChange& change)
{
  share_velocities();
  double sums[4] = {change.sum_change_sq, change.sum_scale_sq, change.sum_scale, change.contacts};
  MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, fix.world);
  // The largest change matters to the maximum norm only: spare the quadratic one a reduction.
  if (fix.contact_step.settings().solver.norm == cd::ConvergenceNorm::maximum)
    MPI_Allreduce(MPI_IN_PLACE, &change.max_change, 1, MPI_DOUBLE, MPI_MAX, fix.world);
  change.sum_change_sq = sums[0];
  change.sum_scale_sq = sums[1];
  change.sum_scale = sums[2];
  change.contacts = sums[3];
}

bool FixContactDynamics::RankExchange::on_any_rank(bool here)
{
  int mine = here ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, fix.world);
  return any != 0;
}

int FixContactDynamics::pack_forward_comm(int n, int* list, double* buf, int pbc_flag, int* pbc)
{
  if (forward_field == ForwardField::obstacle_travel) return obstacles.pack_travel(n, list, buf);
  int m = 0;
  if (sending_image_shifts) {
    const int across_x = pbc_flag ? pbc[0] : 0, across_y = pbc_flag ? pbc[1] : 0;
    for (int k = 0; k < n; k++) {
      buf[m++] = image_shift[list[k]].x + across_x;
      buf[m++] = image_shift[list[k]].y + across_y;
    }
    return m;
  }
  for (int k = 0; k < n; k++) {
    const cd::BodyVelocity& velocity = bodies.velocity[body_of_atom[list[k]]];
    buf[m++] = velocity.vx;
    buf[m++] = velocity.vy;
    buf[m++] = velocity.spin;
  }
  return m;
}

void FixContactDynamics::unpack_forward_comm(int n, int first, double* buf)
{
  if (forward_field == ForwardField::obstacle_travel) return obstacles.unpack_travel(n, first, buf);
  int m = 0;
  if (sending_image_shifts) {
    for (int g = first; g < first + n; g++, m += 2)
      image_shift[g] = {static_cast<int>(buf[m]), static_cast<int>(buf[m + 1])};
    return;
  }
  for (int g = first; g < first + n; g++, m += 3) {
    if (body_of_atom[g] != 1 + g) continue;  // an image: its body is updated elsewhere
    const cd::BodyVelocity velocity{buf[m], buf[m + 1], buf[m + 2]};
    bodies.velocity[1 + g] = velocity;
    ghost_reference[1 + g] = velocity;
  }
}

cd::BodyVelocity FixContactDynamics::velocity_change_of_ghost(int g) const
{
  if (body_of_atom[g] != 1 + g) return {};  // images of owned atoms change their owner directly
  const cd::BodyVelocity& now = bodies.velocity[1 + g];
  const cd::BodyVelocity& before = ghost_reference[1 + g];
  return {now.vx - before.vx, now.vy - before.vy, now.spin - before.spin};
}

int FixContactDynamics::pack_reverse_comm(int n, int first, double* buf)
{
  int m = 0;
  for (int g = first; g < first + n; g++) {
    const cd::BodyVelocity change = velocity_change_of_ghost(g);
    buf[m++] = change.vx;
    buf[m++] = change.vy;
    buf[m++] = change.spin;
  }
  return m;
}

void FixContactDynamics::unpack_reverse_comm(int n, int* list, double* buf)
{
  int m = 0;
  for (int k = 0; k < n; k++, m += 3) {
    cd::BodyVelocity& velocity = bodies.velocity[body_of_atom[list[k]]];
    velocity.vx += buf[m];
    velocity.vy += buf[m + 1];
    velocity.spin += buf[m + 2];
  }
}

// The contact part of the pressure tensor, (1 / (A dt)) cd::branch_impulse_sums, as LAMMPS's
// pair virial: into the output vector (xx, yy, xy, yx) and, summed per rank, the fix's virial
// (energy units) for compute pressure.
void FixContactDynamics::tally_contact_stress()
{
  const cd::BranchImpulseSums sums = cd::branch_impulse_sums(contact_step.contacts().solved);
  double local[4] = {sums.xx, sums.yy, sums.xy, sums.yx};  // m N s
  const double dt = update->dt;
  if (vflag_global) {
    virial[0] += local[0] / dt;
    virial[1] += local[1] / dt;
    virial[3] += local[2] / dt;
  }
  MPI_Allreduce(local, contact_pressure, 4, MPI_DOUBLE, MPI_SUM, world);
  const double area = domain->xprd * domain->yprd;
  for (double& value : contact_pressure) value /= area * dt;
}

// One row per loaded contact, at the predicted configuration (before the corrector): atom IDs
// (0 for a wall), wall number (0 for a pair of atoms), p_n, p_t, the contact point midway
// across the gap.
void FixContactDynamics::fill_local_output()
{
  if (loaded_contacts > local_rows_allocated) {
    local_rows_allocated = loaded_contacts;
    memory->destroy(array_local);
    memory->create(array_local, local_rows_allocated, output_columns, "contact/dynamics:array_local");
  }
  int row = 0;
  contact_step.contacts().for_each_loaded([&](const cd::PairKey& key, const cd::Contact& c) {
    const int a = c.body_a - 1;  // an owned atom
    const cd::Disk disk_a = disk_at_solve(a);
    const bool wall = c.body_b == cd::world_body;
    const cd::Point point = cd::contact_point(c, disk_a.x, disk_a.y);
    double* out = array_local[row++];
    out[0] = atom->tag[a];
    out[1] = wall ? 0 : atom->tag[c.body_b - 1];
    out[2] = wall ? wall_number(key.partner) : 0;
    out[3] = c.impulse.n;
    out[4] = c.impulse.t;
    out[5] = point.x;
    out[6] = point.y;
  });
  size_local_rows = row;
}

double FixContactDynamics::compute_vector(int n)
{
  switch (n) {
    case 0: return last_report.iterations;
    case 1: return last_report.residual;
    case 2: return solved_contacts_total;
    case 3: return loaded_contacts_total;
    case 4:
    case 5:
      // Within a run and once the fix has set up (an earlier fix may read it before).
      if (update->whichflag != 0 && mean_diameter > 0.0 && overlaps_measured_at != update->ntimestep)
        measure_overlaps();
      return n == 4 ? max_overlap : mean_overlap;
    case 6: return last_report.converged ? 1.0 : 0.0;
    case 7: return total_iterations;
    case 8: return total_unconverged_steps;
    case 9: return total_steps;
    case 10: return full_sweep_work;
    case 11: return last_report.solves;
    case 12: return contact_pressure[0];
    case 13: return contact_pressure[1];
    case 14: return contact_pressure[2];
    case 15: return contact_pressure[3];
  }
  return 0.0;
}

/* ----------------------------------------------------------------------
   restart and per-atom life cycle
------------------------------------------------------------------------- */

namespace {
// The global restart record: a negative version tag (older files start with the iteration
// total, never negative), the totals, the step grid's level and position (-1: none), the time,
// and the grid the level refers to (dt_max, steps per alignment period).
constexpr double restart_version = -3.0;
constexpr double restart_version_without_grid = -2.0;
}  // namespace

void FixContactDynamics::write_restart(FILE* fp)
{
  if (comm->me != 0) return;
  const bool known = settings.adaptive_step() && step_clock.known;
  const double elapsed = current_time();
  const double record[9] = {restart_version,
                            total_iterations,
                            total_unconverged_steps,
                            total_steps,
                            known ? step_clock.level : -1.0,
                            known ? static_cast<double>(step_clock.steps_into_period) : -1.0,
                            elapsed,
                            settings.step_grid.dt_max,
                            static_cast<double>(settings.step_grid.steps_per_align)};
  const int size = sizeof(record);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(record, sizeof(double), 9, fp);
}

void FixContactDynamics::restart(char* buf)
{
  const auto* record = reinterpret_cast<const double*>(buf);
  const bool versioned = record[0] == restart_version || record[0] == restart_version_without_grid;
  const double* totals = versioned ? record + 1 : record;
  total_iterations = totals[0];
  total_unconverged_steps = totals[1];
  total_steps = totals[2];
  // This LAMMPS version's restart files do not keep the time (the next run would start it at 0),
  // and with a varying step the step count does not give it: the fix keeps it. Files of earlier
  // versions of the fix came from fixed steps: step x dt.
  set_clock(versioned ? totals[5] : static_cast<double>(update->ntimestep) * update->dt);
  // The level and position hold on the grid they were written on only.
  const bool same_grid = record[0] == restart_version && totals[6] == settings.step_grid.dt_max &&
                         static_cast<int>(totals[7]) == settings.step_grid.steps_per_align;
  if (!same_grid || totals[3] < 0.0) return;
  step_clock = {static_cast<int>(totals[3]), static_cast<long long>(totals[4]), true};
}

double FixContactDynamics::current_time() const
{
  if (update->ntimestep == 0) return 0.0;
  return update->atime + static_cast<double>(update->ntimestep - update->atimestep) * update->dt;
}

void FixContactDynamics::set_clock(double time)
{
  update->atime = time;
  update->atimestep = update->ntimestep;
}

void FixContactDynamics::grow_arrays(int nmax)
{
  memory->grow(history, nmax, history_width, "contact/dynamics:history");
  obstacles.grow(nmax);
}

void FixContactDynamics::copy_arrays(int i, int j, int)
{
  std::memcpy(history[j], history[i], sizeof(double) * cd::impulse_row::used(history[i]));
  obstacles.copy(i, j);
}

void FixContactDynamics::set_arrays(int i)
{
  cd::impulse_row::clear(history[i]);
  obstacles.set_start(i, atom->x[i]);
}

// The warm-start row, then the obstacle start.
int FixContactDynamics::pack_exchange(int i, double* buf)
{
  const int n = cd::impulse_row::used(history[i]);
  std::memcpy(buf, history[i], sizeof(double) * n);
  return n + obstacles.pack(i, buf + n);
}

int FixContactDynamics::unpack_exchange(int nlocal, double* buf)
{
  const int n = cd::impulse_row::used(buf);
  std::memcpy(history[nlocal], buf, sizeof(double) * n);
  return n + obstacles.unpack(nlocal, buf + n);
}

int FixContactDynamics::pack_restart(int i, double* buf)
{
  const int n = cd::impulse_row::used(history[i]);
  buf[0] = n + 1;  // LAMMPS convention: the first value counts the values of this fix
  std::memcpy(buf + 1, history[i], sizeof(double) * n);
  return n + 1;
}

void FixContactDynamics::unpack_restart(int nlocal, int nth)
{
  double** extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  const int count = cd::impulse_row::entries(&extra[nlocal][m]);
  if (count > settings.max_contacts)
    error->one(FLERR,
               "Fix contact/dynamics: restart holds {} contacts for atom {}, more than "
               "max_contacts {}",
               count, atom->tag[nlocal], settings.max_contacts);
  std::memcpy(history[nlocal], &extra[nlocal][m], sizeof(double) * cd::impulse_row::width(count));
}

int FixContactDynamics::size_restart(int i)
{
  return 1 + cd::impulse_row::used(history[i]);
}

int FixContactDynamics::maxsize_restart()
{
  return 1 + history_width;
}

double FixContactDynamics::memory_usage()
{
  double bytes = static_cast<double>(atom->nmax) * history_width * sizeof(double);
  bytes += obstacles.memory_usage(atom->nmax);
  bytes += static_cast<double>(contact_step.contacts().memory_bytes());
  bytes += bodies.velocity.capacity() * (2 * sizeof(cd::BodyVelocity) + sizeof(cd::BodyInertia));
  bytes += static_cast<double>(local_rows_allocated) * output_columns * sizeof(double);
  return bytes;
}
