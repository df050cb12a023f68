#include "fix_contact_dynamics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>
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

#include "cd/kinematics.h"
#include "cd/periodic_box.h"
#include "cd/problem_file.h"
#include "fix_contact_dynamics_checks.h"
#include "fix_contact_dynamics_listed_pairs.h"
#include "fix_contact_dynamics_rank_exchange.h"

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

constexpr int output_columns = 7;
// Subdomains narrower than this many contact cutoffs are reported: there every grain is a
// ghost of a neighbouring rank, and a chute's flow measurably depended on the rank count
// (doc/benchmarks.md).
constexpr double narrow_subdomain_cutoffs = 2.0;

// Partners of wall contacts in the per-atom store are negative, atom IDs positive: a line or
// segment w has three (its interior and ends), region walls follow them (region_wall_partner).
constexpr int partners_per_line_wall = 3;
std::int64_t wall_partner(int wall_index, cd::WallPart part)
{
  return -(partners_per_line_wall * std::int64_t{wall_index} + static_cast<int>(part) + 1);
}

}  // namespace

std::int64_t FixContactDynamics::region_wall_partner(int wall, int face) const
{
  const std::int64_t lines = partners_per_line_wall * std::int64_t(settings.walls.size());
  return -(lines + std::int64_t{wall} * RegionWalls::faces_per_region + face + 1);
}

// The 1-based wall number of a wall partner, among all walls in the order given.
int FixContactDynamics::wall_number(std::int64_t partner) const
{
  const std::int64_t slot = -partner - 1;
  const std::int64_t lines = partners_per_line_wall * std::int64_t(settings.walls.size());
  if (slot < lines) return settings.wall_numbers[slot / partners_per_line_wall];
  return settings.region_walls[(slot - lines) / RegionWalls::faces_per_region].number;
}

// A key's partner for messages: "atom ID" or "wall N".
std::string FixContactDynamics::partner_name(std::int64_t partner) const
{
  if (partner > 0) return fmt::format("atom {}", partner);
  return fmt::format("wall {}", wall_number(partner));
}

/* ---------------------------------------------------------------------- */

FixContactDynamics::FixContactDynamics(LAMMPS* lmp, int narg, char** arg) : Fix(lmp, narg, arg)
{
  if (domain->dimension != 2) error->all(FLERR, "Fix contact/dynamics requires dimension 2");
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR, "Fix contact/dynamics requires atom_style sphere (per-atom radius, rmass, omega)");
  fix_keywords::FixCommand command =
      fix_keywords::parse_settings(narg, arg, atom->ntypes, domain->boxlo, domain->boxhi, error);
  settings = std::move(command.fix);
  step_grid = std::make_unique<StepGridControl>(lmp, settings.step_grid, settings.travel_fraction,
                                                [this](const std::string& why) {
                                                  output->write_restart(update->ntimestep);
                                                  error->all(FLERR, why);
                                                });
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
  comm_forward = 3;         // vx, vy, spin of a body
  comm_reverse = 3;         // the change of a ghost's vx, vy, spin over one sweep
  virial_global_flag = 1;   // the contact stress, into compute pressure with fix_modify virial yes
  virial_peratom_flag = 1;  // and atom by atom into compute stress/atom
  thermo_virial = 0;

  // With a varying step the clock is LAMMPS's time, not step x dt; step 0 is time 0 (this
  // version's reset_timestep keeps the time already run, e.g. a deposition before the chute).
  if (update->ntimestep == 0) set_lammps_time(*update, 0.0);

  impulses = std::make_unique<ImpulseStore>(memory, settings.max_contacts);
  maxexchange = impulses->width() + ObstacleMotion::values_per_atom;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) impulses->clear(i);
}

FixContactDynamics::~FixContactDynamics()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(array_local);
}

int FixContactDynamics::setmask()
{
  int mask = INITIAL_INTEGRATE | FINAL_INTEGRATE | PRE_EXCHANGE;
  if (settings.disc_density > 0.0) mask |= PRE_FORCE;
  if (step_grid->on()) mask |= END_OF_STEP;
  return mask;
}

/* ---------------------------------------------------------------------- */

void FixContactDynamics::init()
{
  distributed = comm->nprocs > 1;
  sheared_cell.check_box_changes(*this, step_grid->on());
  if (!comm->ghost_velocity)
    error->all(FLERR, "Fix contact/dynamics requires ghost velocities: use comm_modify vel yes");
  if (atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "Fix contact/dynamics requires an atom map: use atom_modify map hash");
  fix_checks::insertion_map(lmp);
  if (step_grid->on()) fix_checks::fixed_step_fixes(lmp);
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
  fix_checks::integrators(lmp, *this);
  if (!settings.pair_forces) fix_checks::pair_style(lmp, *this);
  check_alert();
  region_walls.init();

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
  overlaps.look_at(list, groupbit);
}

// Pairs are looked at only among the neighbour list's, listed out to a gap of the skin at most:
// a larger alert would ask for pairs the list does not hold.
void FixContactDynamics::check_alert()
{
  const std::optional<double>& alert = contact_step.settings().alert;
  if (alert && *alert > neighbor->skin)
    error->all(FLERR,
               "Fix contact/dynamics: alert {} is larger than the neighbour skin {}: pairs that far apart are "
               "not listed; lower alert or raise the skin (neighbor command)",
               *alert, neighbor->skin);
}

// At setup and whenever the atom count changed (insertions): the masses checked, the mean
// diameter (the unit of the overlap outputs) and the default alert distance that follows it.
void FixContactDynamics::survey_group()
{
  const std::optional<double> areal_density = fix_checks::disk_masses(lmp, *this);
  if (areal_density && settings.disc_density <= 0.0 && !mass_rule_reported && comm->me == 0)
    utils::logmesg(lmp,
                   "Fix contact/dynamics: the grains of group {} have one radius: their masses are disks of areal "
                   "density {:.6g} (m = pi r^2 rho); were they set as spheres (set density), use set density/disc\n",
                   group->names[igroup], *areal_density);
  mass_rule_reported = mass_rule_reported || areal_density.has_value();
  mean_diameter = group_mean_diameter();
  contact_step.set_mean_diameter(mean_diameter);
  natoms_surveyed = atom->natoms;
  obstacles.find(*atom, groupbit, world);
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

void FixContactDynamics::setup(int vflag)
{
  // No step is solved at a run's start: the per-atom virial is zero there (the global one keeps
  // the last step's), in rows for every owned atom.
  if (thermo_virial && (vflag & (VIRIAL_ATOM | VIRIAL_CENTROID))) {
    grow_peratom_virial();
    contact_stress.per_atom(cd::StepContacts{}, vatom, atom->nlocal);
  }
  if (settings.disc_density > 0.0) assign_disc_masses();
  survey_group();
  check_subdomains();
  region_walls.record_start();
  overlaps.warn_initial(sheared_cell.box_now(), mean_diameter);
  obstacles.record_starts(*atom, groupbit);
  run_statistics.clear();
  if (step_grid->on()) step_grid->setup(groupbit);
}

void FixContactDynamics::end_of_step()
{
  step_grid->end_of_step(groupbit);
}

// A ghost must be one hop from its owner: the exchange sends each ghost's velocity change
// straight back to the rank that owns it.
void FixContactDynamics::check_subdomains()
{
  const double cutoff = 2.0 * covered_radius + neighbor->skin;
  if (!distributed) return;
  const double width = fix_checks::narrowest_split_subdomain(lmp);
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

// A grain LAMMPS is about to wrap across a moving side goes where the step meets its image.
void FixContactDynamics::pre_exchange()
{
  sheared_cell.lead_wrapped_grains(step_parameters());
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
  region_walls.begin_step(step_parameters());
  sheared_cell.begin_step(step_parameters());
  if (sheared_cell.deforms()) {
    sheared_cell.clear_image_shifts(atom->nlocal + atom->nghost);
    forward(ForwardField::image_shift);
  }
  gather_bodies();
  RankExchange exchange(lmp, *this, contact_step.settings().solver.norm);
  LammpsHost host(*this);
  const cd::StepReport report = contact_step.solve(bodies, update->dt, host, distributed ? &exchange : nullptr);
  last_report = report.solve;
  save_hard_problem();  // heights at x_m, before the corrector moves the atoms
  loaded_contacts = report.loaded_contacts;
  store_impulses();
  contact_stress.after_step(contact_step.contacts(), vflag_global ? virial : nullptr);
  if (vflag_atom) tally_peratom_virial();
  fill_local_output();
  write_back_motion();
  reduce_step_outputs();
  if (obstacles.present()) obstacles.record_starts(*atom, groupbit);

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
      fmt::format("step {} time {} dt {} sweeps {} converged {} final norm {}", update->ntimestep, lammps_time(*update),
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
  if (!obstacles.present()) return;
  obstacles.measure_travel(*atom, *domain, groupbit);
  const double step_limit = 0.5 * neighbor->skin;
  for (int i = 0; i < atom->nlocal; i++) {
    const cd::Displacement& s = obstacles.travel(i);
    if (std::hypot(s.dx, s.dy) > step_limit)
      error->one(FLERR,
                 "Fix contact/dynamics: obstacle atom {} moved {} in step {}, more than half the neighbour skin {}; "
                 "reduce the time step or raise the skin",
                 atom->tag[i], std::hypot(s.dx, s.dy), update->ntimestep, neighbor->skin);
  }
  forward(ForwardField::obstacle_travel);
}

void FixContactDynamics::forward(ForwardField field)
{
  forward_field = field;
  comm->forward_comm_fix(this, field == ForwardField::velocity ? comm_forward : 2);
  forward_field = ForwardField::velocity;
}

cd::Disk FixContactDynamics::disk_at_solve(int i) const
{
  return obstacles.disk_at_solve(i, {atom->x[i][0], atom->x[i][1], atom->radius[i]}, step_parameters());
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
    sheared_cell.image_velocity(i, image_vx, image_vy);
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
    forward(ForwardField::velocity);
  }
}

// The listed pairs whose gap lies above their reach plus from_margin and at most their reach
// plus to_margin (cd::PairReach), and the walls likewise, offered to the step's contacts.
void FixContactDynamics::LammpsHost::collect_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                                   cd::StepContacts& contacts)
{
  if (!std::isfinite(from_margin)) fix.overlaps.begin_look();
  fix.collect_grain_pairs(reach, from_margin, to_margin, contacts);
  fix.collect_wall_pairs(reach, from_margin, to_margin, contacts);
  fix.collect_region_wall_pairs(reach, from_margin, to_margin, contacts);
}

void FixContactDynamics::collect_grain_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                             cd::StepContacts& contacts)
{
  const int* type = atom->type;
  const int* mask = atom->mask;
  // An image across a side of a deforming box moves at its body's velocity plus the box's (j is
  // the ghost; i is owned): LAMMPS placed it with the box at the start of the step, the step
  // meets it at the predicted configuration, and its look reaches as far as its speed.
  const cd::StepParameters step = step_parameters();
  // Positions as they are unless obstacles may have moved or the box deforms (no lookups).
  const bool displaced = obstacles.present() || sheared_cell.deforms();
  double** x = atom->x;
  const double* radius = atom->radius;
  for_each_listed_pair(*list, *atom, [&](int i, int j) {
    if (!(mask[i] & groupbit) && !(mask[j] & groupbit)) return;
    const int body_j = body_of_atom[j];
    double image_vx = 0.0, image_vy = 0.0, image_reach = 0.0;
    cd::Disk disk_i{x[i][0], x[i][1], radius[i]}, disk_j{x[j][0], x[j][1], radius[j]};
    if (displaced) {
      sheared_cell.image_velocity(j, image_vx, image_vy);
      image_reach = cd::image_reach(image_vx, image_vy, step);
      disk_i = disk_at_solve(i);
      disk_j = disk_at_solve(j);
      const cd::Displacement lead = cd::image_lead(image_vx, image_vy, step);
      disk_j.x += lead.dx;
      disk_j.y += lead.dy;
    }
    if (!reach.in_look(1 + i, disk_i, body_j, disk_j, from_margin + image_reach, to_margin + image_reach)) return;
    if (body_j == 1 + i)
      error->one(FLERR, "Fix contact/dynamics: atom {} touches its own periodic image; the cell is too short",
                 atom->tag[i]);
    overlaps.watch_pair(i, j);
    const cd::PairKey key = pair_key(i, j);
    cd::ContactGeometry geometry = cd::disk_disk_geometry(1 + i, disk_i, body_j, disk_j);
    geometry.image_vx = image_vx;
    geometry.image_vy = image_vy;
    contacts.offer(geometry, settings.law(type[i], type[j]), key, impulses->carried(key));
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

void FixContactDynamics::collect_wall_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                            cd::StepContacts& contacts)
{
  if (settings.walls.empty()) return;
  // A wall's images move with a deforming box, one edge vector at the speeds below at most.
  const cd::PeriodicBox& step_box = sheared_cell.step_box();
  const double image_reach = cd::wall_image_reach(step_box, step_parameters());
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
      overlaps.watch_wall(i, w);
      const cd::PairKey key{i, wall_partner(w, touch->part)};
      contacts.offer(touch->geometry, settings.walls[w].law, key, impulses->carried(key));
    }
  }
}

// Region walls stand where the step meets them (RegionWalls::AtSolve); a moving one's surface
// comes closer in the rest of the step, as a deforming box's images do.
void FixContactDynamics::collect_region_wall_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                                   cd::StepContacts& contacts)
{
  if (settings.region_walls.empty()) return;
  const RegionWalls::AtSolve at_solve(region_walls);
  const double advance = step_parameters().advance();
  double** x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const cd::Disk disk{x[i][0], x[i][1], atom->radius[i]};
    const double reach_i = reach.reach(1 + i);
    for (int w = 0; w < region_walls.count(); w++)
      for (const RegionWalls::Touch& touch : region_walls.touches(w, 1 + i, disk, reach_i + to_margin, advance)) {
        if (!reach.wall_in_look(1 + i, touch.geometry.gap, from_margin + touch.approach)) continue;
        overlaps.watch_region_wall(i, w);
        const cd::PairKey key{i, region_wall_partner(w, touch.face)};
        contacts.offer(touch.geometry, region_walls.setting(w).law, key, impulses->carried(key));
      }
  }
}

/* ----------------------------------------------------------------------
   Warm start: the atom with the smaller ID of a pair (or the atom touching a wall) stores the
   impulses of its loaded contacts, keyed by partner atom ID (or wall slot). Seen from either
   body the pair has the same (p_n, p_t): swapping a and b flips both normal and tangent.
------------------------------------------------------------------------- */

// The step's loaded contacts replace what the owned atoms carried.
void FixContactDynamics::store_impulses()
{
  for (int i = 0; i < atom->nlocal; i++) impulses->clear(i);
  contact_step.contacts().for_each_loaded([&](const cd::PairKey& key, const cd::Contact& contact, double) {
    const cd::Local2 p = contact.impulse;
    if (!std::isfinite(p.n) || !std::isfinite(p.t))
      error->one(FLERR, "Fix contact/dynamics: non-finite impulse between atom {} and {} at step {}",
                 atom->tag[key.row], partner_name(key.partner), update->ntimestep);
    if (!impulses->append(key, p))
      error->one(FLERR, "Fix contact/dynamics: atom {} has more than {} loaded contacts; raise max_contacts",
                 atom->tag[key.row], settings.max_contacts);
  });
}

// Neighbour lists are rebuilt once a grain has moved half the skin; a grain moving more than
// that in one step could pass through a pair the list does not hold: the farthest such grain is
// kept, and the run stops once every rank knows (reduce_step_outputs).
void FixContactDynamics::write_back_motion()
{
  const cd::StepParameters step = step_parameters();
  const double step_limit_sq = 0.25 * neighbor->skin * neighbor->skin;
  farthest_mover = {0.0, 0};
  too_far_movers = 0;
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
    if (moved.dx * moved.dx + moved.dy * moved.dy > step_limit_sq) {
      ++too_far_movers;
      const double distance = std::hypot(moved.dx, moved.dy);
      if (distance > farthest_mover.distance) farthest_mover = {distance, static_cast<int>(atom->tag[i])};
    }
    v[i][0] = velocity.vx;
    v[i][1] = velocity.vy;
    omega[i][2] = velocity.spin;
    const cd::Displacement shift = cd::corrected_motion(velocity, step);
    x[i][0] += shift.dx;
    x[i][1] += shift.dy;
  }
}

// The step's output vector: sums over ranks, with the count of grains that moved too far in the
// same reduction. A stop is then every rank's (one error line, no MPI abort), naming the farthest.
void FixContactDynamics::reduce_step_outputs()
{
  const double local_sums[4] = {static_cast<double>(contact_step.contacts().solved.size()),
                                static_cast<double>(loaded_contacts), last_report.contact_updates,
                                static_cast<double>(too_far_movers)};
  double sums[4];
  MPI_Allreduce(local_sums, sums, 4, MPI_DOUBLE, MPI_SUM, world);
  solved_contacts_total = sums[0];
  loaded_contacts_total = sums[1];
  full_sweep_work = sums[0] > 0.0 ? sums[2] / sums[0] : 0.0;
  if (sums[3] == 0.0) return;
  Mover farthest{0.0, 0};
  MPI_Allreduce(&farthest_mover, &farthest, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  error->all(FLERR,
             "Fix contact/dynamics: atom {} moved {} in step {}, more than half the neighbour skin {}; reduce the "
             "time step or raise the skin",
             farthest.tag, farthest.distance, update->ntimestep, neighbor->skin);
}

// Between runs outputs are read without the run's lists: measure the last step's now.
void FixContactDynamics::post_run()
{
  if (mean_diameter > 0.0) overlaps.measure_if_stale(sheared_cell.box_now(), mean_diameter, solved_contacts_total);
  if (comm->me == 0)
    utils::logmesg(lmp, "Fix contact/dynamics {} solver: {}\n", id, cd::describe(run_statistics.summary()));
}

// vatom has a row for every owned and ghost atom: LAMMPS sized it at initial_integrate, before
// atoms arrived from other ranks.
void FixContactDynamics::grow_peratom_virial()
{
  if (atom->nmax <= maxvatom) return;
  maxvatom = atom->nmax;
  memory->destroy(vatom);
  memory->create(vatom, maxvatom, 6, "contact/dynamics:vatom");
}

// The step's contacts atom by atom, on the steps that ask for it (compute stress/atom): a pair
// across a rank boundary is solved by one rank, which leaves the other atom's share on its
// ghost; the owner adds it in (compute stress/atom reads owned atoms' rows only).
void FixContactDynamics::tally_peratom_virial()
{
  grow_peratom_virial();
  contact_stress.per_atom(contact_step.contacts(), vatom, atom->nlocal + atom->nghost);
  if (!distributed) return;  // one rank: the images of an owned atom share its body
  reverse_field = ReverseField::virial;
  comm->reverse_comm_fix(this, static_cast<int>(std::size(peratom_virial_components)));
  reverse_field = ReverseField::velocity_change;
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
  contact_step.contacts().for_each_loaded([&](const cd::PairKey& key, const cd::Contact& c, double gap) {
    const int a = c.body_a - 1;  // an owned atom
    const cd::Disk disk_a = disk_at_solve(a);
    const bool wall = c.body_b == cd::world_body;
    const cd::Point point = cd::contact_point(c, gap, disk_a.x, disk_a.y);
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
      if (update->whichflag != 0 && mean_diameter > 0.0)
        overlaps.measure_if_stale(sheared_cell.box_now(), mean_diameter, solved_contacts_total);
      return n == 4 ? overlaps.deepest() : overlaps.mean();
    case 6: return last_report.converged ? 1.0 : 0.0;
    case 7: return total_iterations;
    case 8: return total_unconverged_steps;
    case 9: return total_steps;
    case 10: return full_sweep_work;
    case 11: return last_report.solves;
    case 12:
    case 13:
    case 14:
    case 15: return contact_stress.component(n - 12);
  }
  return 0.0;
}

double FixContactDynamics::memory_usage()
{
  double bytes = impulses->memory_usage(atom->nmax);
  bytes += obstacles.memory_usage(atom->nmax);
  bytes += static_cast<double>(contact_step.contacts().memory_bytes());
  bytes += bodies.velocity.capacity() * (2 * sizeof(cd::BodyVelocity) + sizeof(cd::BodyInertia));
  bytes += static_cast<double>(local_rows_allocated) * output_columns * sizeof(double);
  bytes += static_cast<double>(maxvatom) * 6 * sizeof(double);  // the per-atom virial, if asked for
  return bytes;
}
