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

#include <random>
#include <vector>

#include "cd/detection.h"
#include "cd/gauss_seidel.h"
#include "cd/time_step.h"
#include "cd/walls.h"
#include "fix.h"

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
  void final_integrate() override;
  void end_of_step() override;
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
  // Who touches whom, for warm starts and the local output.
  struct ContactRecord {
    tagint atom_a = 0;         // atom ID of body a (always an owned atom)
    tagint atom_b = 0;         // atom ID of body b, 0 for a wall
    int wall = 0;              // 1-based wall index, 0 for an atom pair
    int history_atom = -1;     // owned atom whose row stores the warm start: the smaller ID of a pair
    double history_key = 0.0;  // the partner in that row: the other atom ID, or -(wall slot)
    double point_x = 0.0;      // contact point at the predicted configuration
    double point_y = 0.0;

    // Atoms of local indices i and j (i owned): the warm start lives with the smaller ID.
    static ContactRecord between_atoms(const tagint* tag, int i, int j, const cd::ContactGeometry& geometry);
    // Owned atom i against wall slot `slot` (0-based) at the part `part` of that wall.
    static ContactRecord against_wall(const tagint* tag, int i, int slot, cd::WallPart part,
                                      const cd::ContactGeometry& geometry);
  };

  // Per-iteration exchange across MPI ranks: ghost velocity changes summed into their owners
  // (reverse comm), owners' velocities copied to ghosts (forward comm), norm sums reduced.
  class RankExchange : public cd::SweepExchange {
   public:
    explicit RankExchange(FixContactDynamics& fix) : fix(fix) {}
    void after_sweep(cd::SweepChange& change) override;
    bool on_any_rank(bool here) override;
    void synchronise_velocities();

   private:
    FixContactDynamics& fix;
  };
  friend class RankExchange;

  // The wider look cd::solve_step may ask for: the neighbour list again, further out.
  class NeighbourPairs : public cd::PairCollector {
   public:
    explicit NeighbourPairs(FixContactDynamics& fix) : fix(fix) {}
    void collect_between(double from_margin, double to_margin) override { fix.collect_pairs(from_margin, to_margin); }

   private:
    FixContactDynamics& fix;
  };

  enum class ContactOrder { fixed, shuffled };

  // --- settings (from the command line) ---
  double theta = 0.5;
  cd::SolverSettings solver_settings;
  ContactOrder order = ContactOrder::fixed;
  bool warm_start = true;
  int max_contacts = 12;
  double disc_density = 0.0;     // > 0: masses reset to pi r^2 rho
  double alert_distance = -1.0;  // candidate pairs: gap closed at free velocity <= alert (m)
  bool alert_given = false;
  bool narrow_subdomains_reported = false;  // the narrow-subdomain warning is given once per fix
  bool pair_forces = false;                 // a pair style may act on the group's pairs too
  int law_types = 0;                        // atom types when the fix was defined
  std::vector<cd::ContactLaw> type_laws;    // (law_types+1)^2, row-major
  std::vector<cd::Wall> walls;
  std::mt19937_64 shuffle_rng;
  // The step that follows the flow (dt_max given): the grid, the travel bound as a fraction of
  // the neighbour skin, and where the run stands on the grid.
  bool adaptive_step = false;
  cd::StepGrid step_grid;
  double dt_align = 0.0;  // s; 0: dt_max
  double travel_fraction = 0.4;
  int step_level = 0;
  long long steps_into_period = 0;
  bool step_state_known = false;  // level and position set (by a run or a restart)

  // --- per-step state ---
  class NeighList* list = nullptr;
  double covered_radius = 0.0;                    // largest radius the neighbour/ghost cutoff was set for
  double mean_diameter = 0.0;                     // of the group at natoms_surveyed atoms (m)
  bigint natoms_surveyed = -1;                    // atom count at the last survey_group
  cd::BodySet bodies;                             // world, owned atoms, then ghosts owned elsewhere
  std::vector<int> body_of_atom;                  // body of every owned and ghost atom this step
  std::vector<cd::BodyVelocity> ghost_reference;  // ghost velocities at the last forward comm
  bool distributed = false;                       // more than one rank: exchange every sweep
  cd::PairReach reach;                            // which listed pairs a step looks at
  cd::StepContacts pairs;                         // solved and watched pairs of this step
  std::vector<ContactRecord> records;             // of each solved pair, in sweep order
  std::vector<ContactRecord> watched_records;     // indexed by cd::WatchedPair::record
  std::vector<int> promoted_records;              // scratch of solve_contacts
  std::vector<cd::Contact> reordered_contacts;    // scratch of reorder_contacts
  std::vector<ContactRecord> reordered_records;
  cd::SolveReport last_report;
  double max_overlap = 0.0, mean_overlap = 0.0;                     // in units of the mean diameter, over all ranks
  double solved_contacts_total = 0.0, loaded_contacts_total = 0.0;  // over all ranks
  double full_sweep_work = 0.0;  // the step's local solves over all ranks / solved contacts
  int loaded_contacts = 0;       // on this rank

  // --- running totals (kept across restarts) ---
  double total_iterations = 0.0, total_unconverged_steps = 0.0, total_steps = 0.0;

  // --- per-atom warm-start store: [count, (partner key, p_n, p_t) x max_contacts] ---
  double** history = nullptr;
  int history_width = 0;

  // --- local output: one row per loaded contact ---
  int local_rows_allocated = 0;

  void parse_arguments(int narg, char** arg);
  int parse_wall(int iarg, int narg, char** arg);
  void parse_type_law(const char* keyword, int iarg, int narg, char** arg, bool friction);
  void check_insertion_map();
  void check_integrators();
  void check_pair_style();
  void survey_group();
  void check_disk_masses();
  double group_mean_diameter();
  void assign_disc_masses();
  void request_neighbor_list();

  const cd::ContactLaw& law(int itype, int jtype) const;
  void check_subdomains();
  double narrowest_split_subdomain();
  void warn_initial_overlaps();
  cd::PeriodicBox periodic_box() const;
  void map_bodies();
  void gather_bodies();
  cd::BodyVelocity velocity_change_of_ghost(int ghost) const;
  void collect_pairs(double from_margin, double to_margin);
  void collect_grain_pairs(double from_margin, double to_margin);
  void collect_wall_pairs(double from_margin, double to_margin);
  void add_pair(const cd::ContactGeometry&, const cd::ContactLaw&, const ContactRecord&, bool during_solve);
  void shuffle_contacts();
  void interleave_contacts();
  void reorder_contacts(const std::vector<int>& permutation);
  void solve_contacts();
  void load_warm_start();
  void store_warm_start();
  void append_history(int atom_index, double key, cd::Local2 impulse);
  void write_back_motion();
  void reduce_step_outputs(const cd::OverlapSums& overlaps);
  void init_step_grid();
  void choose_step_level();
  void set_timestep(double dt);
  double current_time() const;  // LAMMPS's time now (s)
  void set_clock(double time);  // sets it
  void fill_local_output();
};

}  // namespace LAMMPS_NS

#endif
#endif
