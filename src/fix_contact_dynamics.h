/* Rigid-disk non-smooth Contact Dynamics (Moreau–Jean, nonlinear Gauss–Seidel) as a LAMMPS fix.
   This class is the adapter: it turns LAMMPS atoms, neighbour lists and walls into the solver
   core's bodies and contacts (src/cd/), runs the core, and writes velocities, positions and
   outputs back. The physics lives in the core. */

#ifdef FIX_CLASS
// clang-format off
FixStyle(contact/dynamics,FixContactDynamics);
// clang-format on
#else

#ifndef LMP_FIX_CONTACT_DYNAMICS_H
#define LMP_FIX_CONTACT_DYNAMICS_H

#include <memory>
#include <vector>

#include "cd/detection.h"
#include "cd/solver.h"
#include "cd/solve_statistics.h"
#include "cd/step.h"
#include "cd/walls.h"
#include "fix.h"
#include "fix_contact_dynamics_contact_stress.h"
#include "fix_contact_dynamics_impulse_store.h"
#include "fix_contact_dynamics_obstacles.h"
#include "fix_contact_dynamics_overlaps.h"
#include "fix_contact_dynamics_settings.h"
#include "fix_contact_dynamics_sheared_cell.h"
#include "fix_contact_dynamics_step_grid.h"

namespace LAMMPS_NS {

class FixContactDynamics : public Fix {
 public:
  FixContactDynamics(class LAMMPS*, int, char**);
  ~FixContactDynamics() override;
  int setmask() override;
  void init() override;
  void init_list(int, class NeighList*) override;
  void setup(int) override;
  void initial_integrate(int) override;
  void pre_force(int) override;
  void pre_exchange() override;
  void final_integrate() override;
  void end_of_step() override;
  void post_run() override;
  double compute_vector(int) override;

  int pack_forward_comm(int, int*, double*, int, int*) override;
  void unpack_forward_comm(int, int, double*) override;
  int pack_reverse_comm(int, int, double*) override;
  void unpack_reverse_comm(int, int*, double*) override;

  void write_restart(FILE*) override;
  void restart(char*) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double*) override;
  int unpack_exchange(int, double*) override;
  int pack_restart(int, double*) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

 private:
  // The step's host (cd::StepHost): pairs from LAMMPS's neighbour list and the walls, each with
  // the impulse it carried in the per-atom store (which travels with the atoms and into restarts).
  class LammpsHost : public cd::StepHost {
   public:
    explicit LammpsHost(FixContactDynamics& fix) : fix(fix) {}
    void collect_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                       cd::StepContacts& contacts) override;

   private:
    FixContactDynamics& fix;
  };
  friend class LammpsHost;

  // --- settings (from the command line) ---
  fix_keywords::FixSettings settings;
  bool narrow_subdomains_reported = false;     // the narrow-subdomain warning is given once per fix
  bool mass_rule_reported = false;             // the areal density of one-radius masses is printed once per fix
  std::unique_ptr<StepGridControl> step_grid;  // the step that follows the flow (dt_max)

  // --- per-step state ---
  class NeighList* list = nullptr;
  double covered_radius = 0.0;                    // largest radius the neighbour/ghost cutoff was set for
  double mean_diameter = 0.0;                     // of the group at natoms_surveyed atoms (m)
  bigint natoms_surveyed = -1;                    // atom count at the last survey_group
  cd::BodySet bodies;                             // world, owned atoms, then ghosts owned elsewhere
  std::vector<int> body_of_atom;                  // body of every owned and ghost atom this step
  std::vector<cd::BodyVelocity> ghost_reference;  // ghost velocities at the last forward comm
  ShearedCell sheared_cell{lmp};                  // the box as the step meets it, its images if it deforms
  bool distributed = false;                       // more than one rank: exchange every sweep
  cd::MoreauJeanStep contact_step;                // the core's step: pairs, order, warm start, solve
  cd::SolveReport last_report;
  cd::SolveStatistics run_statistics;                               // this run's steps, reported at its end (post_run)
  ContactStressGauge contact_stress{lmp};                           // outputs 13-16, the virial
  RegionWalls region_walls{lmp, settings.region_walls};             // LAMMPS regions as walls
  OverlapGauge overlaps{lmp, settings.walls, region_walls};         // outputs 5 and 6, the warning at a run's start
  double solved_contacts_total = 0.0, loaded_contacts_total = 0.0;  // over all ranks
  double full_sweep_work = 0.0;  // the step's local solves over all ranks / solved contacts
  int loaded_contacts = 0;       // on this rank
  // Grains that moved more than half the skin in the step, on this rank, and the farthest of them
  // (the layout of MPI_DOUBLE_INT).
  struct Mover {
    double distance;  // m
    int tag;
  } farthest_mover{0.0, 0};
  int too_far_movers = 0;

  // --- running totals (kept across restarts) ---
  double total_iterations = 0.0, total_unconverged_steps = 0.0, total_steps = 0.0;

  // --- per-atom warm-start store ---
  std::unique_ptr<ImpulseStore> impulses;

  // --- obstacles that other fixes move: their starts travel with the atoms ---
  ObstacleMotion obstacles{memory};
  // What a forward communication carries (forward): bodies' velocities (comm_forward values an
  // atom) unless an obstacle's travel or an image's shift (2 values) is asked for.
  enum class ForwardField { velocity, obstacle_travel, image_shift } forward_field = ForwardField::velocity;
  // What a reverse communication carries: ghosts' velocity changes over a sweep (comm_reverse
  // values an atom), or their shares of the per-atom virial (peratom_virial_components of vatom).
  enum class ReverseField { velocity_change, virial } reverse_field = ReverseField::velocity_change;
  static constexpr int peratom_virial_components[3] = {0, 1, 3};  // xx, yy, xy: a 2D contact's

  // --- local output: one row per loaded contact ---
  int local_rows_allocated = 0;

  void check_alert();
  void survey_group();
  double group_mean_diameter();
  void assign_disc_masses();
  void request_neighbor_list();

  void check_subdomains();
  void place_obstacles();
  void forward(ForwardField field);
  cd::Disk disk_at_solve(int i) const;
  void map_bodies();
  void gather_bodies();
  cd::BodyVelocity velocity_change_of_ghost(int ghost) const;
  cd::StepParameters step_parameters() const;
  void collect_grain_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                           cd::StepContacts& contacts);
  void collect_wall_pairs(const cd::PairReach& reach, double from_margin, double to_margin, cd::StepContacts& contacts);
  void collect_region_wall_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                 cd::StepContacts& contacts);
  cd::PairKey pair_key(int i, int j) const;
  std::int64_t region_wall_partner(int wall, int face) const;
  int wall_number(std::int64_t partner) const;
  std::string partner_name(std::int64_t partner) const;
  void store_impulses();
  void write_back_motion();
  void reduce_step_outputs();
  void fill_local_output();
  void grow_peratom_virial();
  void tally_peratom_virial();
  void count_solve();
  void save_hard_problem();
};

}  // namespace LAMMPS_NS

#endif
#endif
