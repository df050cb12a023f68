// Domain decomposition: the fix on every rank of the mpirun (ctest: 2, and 4 oversubscribed)
// against the same problem on 1 rank, run side by
// side in one mpirun (the 1-rank instance lives on rank 0 with MPI_COMM_SELF).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "comm.h"
#include "lammps_session.h"
#include "shared_decks.h"
#include "small_deposition.h"

namespace {

using cdtest::LammpsSession;
constexpr double d = cdtest::deposition_d;
const std::string packing_file = "test_mpi_packing.data";

int world_rank()
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

// One value per atom ID over every rank of the session (sum of each owner's value).
std::vector<double> by_id(const LammpsSession& s, const std::function<double(int)>& value)
{
  const auto* atom = s.lmp->atom;
  std::vector<double> mine(atom->natoms, 0.0), all(atom->natoms, 0.0);
  for (int i = 0; i < atom->nlocal; i++) mine[atom->tag[i] - 1] = value(i);
  MPI_Allreduce(mine.data(), all.data(), static_cast<int>(mine.size()), MPI_DOUBLE, MPI_SUM, s.lmp->world);
  return all;
}

struct State {
  std::vector<double> x, y, vx, vy;
  double candidates = 0.0, loaded = 0.0, sweeps = 0.0;
};

State state_of(const LammpsSession& s)
{
  const auto* atom = s.lmp->atom;
  State st;
  st.x = by_id(s, [&](int i) { return atom->x[i][0]; });
  st.y = by_id(s, [&](int i) { return atom->x[i][1]; });
  st.vx = by_id(s, [&](int i) { return atom->v[i][0]; });
  st.vy = by_id(s, [&](int i) { return atom->v[i][1]; });
  st.candidates = s.fix("cd")->compute_vector(2);
  st.loaded = s.fix("cd")->compute_vector(3);
  st.sweeps = s.fix("cd")->compute_vector(7);
  return st;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b, double period = 0.0)
{
  double largest = 0.0;
  for (std::size_t k = 0; k < a.size(); k++) {
    double delta = a[k] - b[k];
    if (period > 0.0) delta -= period * std::nearbyint(delta / period);
    largest = std::max(largest, std::abs(delta));
  }
  return largest;
}

// The packing: 144 grains raining for 30 ms, the first ones landing, written once by rank 0.
// Deliberately not a dense pile: a frictional pile's impulses are not unique, and 1 and 2
// ranks (which order the sweep differently) may then pick different valid solutions; the
// chute statistics compare those runs instead (bench/).
class SeveralRanks : public ::testing::Test {
 protected:
  static void SetUpTestSuite()
  {
    if (world_rank() == 0) {
      LammpsSession maker(MPI_COMM_SELF);
      maker.commands(cdtest::disk_preamble);
      maker.commands(cdtest::small_deposition(2024, "tolerance 1e-4"));
      maker.commands("run 3000");
      maker.commands("write_data " + packing_file);
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }
  static void TearDownTestSuite()
  {
    if (world_rank() == 0) std::remove(packing_file.c_str());
  }

  // The deck on the packing; ranks split the cell along x.
  static void load(LammpsSession& s, const std::string& fix_options)
  {
    s.commands(cdtest::disk_preamble);
    s.commands("processors * 1 1\nboundary p f p\nread_data " + packing_file);
    s.commands(fmt::format(R"(
neighbor {skin} bin
timestep 1e-5
fix grav all gravity 9.81 vector 0 -1 0
fix cd all contact/dynamics 0.5 0.5 wall yplane 0.0 0.5 0.5 {options}
fix 2d all enforce2d
)",
                           fmt::arg("skin", 0.2 * d), fmt::arg("options", fix_options)));
  }

  // Runs the same commands on all ranks of MPI_COMM_WORLD and on 1 rank (rank 0 only).
  void run_both(const std::string& fix_options, const std::string& commands)
  {
    LammpsSession many(MPI_COMM_WORLD);
    load(many, fix_options);
    ASSERT_GE(many.lmp->comm->nprocs, 2);
    many.commands(commands);
    on_many = state_of(many);
    if (world_rank() == 0) {
      LammpsSession one(MPI_COMM_SELF);
      load(one, fix_options);
      one.commands(commands);
      on_one = state_of(one);
    }
  }

  // One step solved tightly (tight_solve) with extra fix keywords on several ranks and on one:
  // the velocities agree as in SameConfigurationGivesSameContactsAndVelocities.
  void expect_one_rank_velocities(const std::string& keywords);

  State on_one, on_many;
};

constexpr const char* tight_solve = "tolerance 1e-12 max_iterations 100000";

void SeveralRanks::expect_one_rank_velocities(const std::string& keywords)
{
  run_both(std::string(tight_solve) + " " + keywords, "run 1");
  if (world_rank() != 0) return;
  EXPECT_GE(on_one.loaded, 15);
  EXPECT_LT(largest_difference(on_many.vx, on_one.vx), 1e-9);
  EXPECT_LT(largest_difference(on_many.vy, on_one.vy), 1e-9);
}

TEST_F(SeveralRanks, SameConfigurationGivesSameContactsAndVelocities)
{
  run_both(tight_solve, "run 1");
  if (world_rank() != 0) return;
  EXPECT_EQ(on_many.candidates, on_one.candidates);
  EXPECT_EQ(on_many.loaded, on_one.loaded);
  EXPECT_GE(on_one.loaded, 15);  // a problem with contacts (the packing's count follows the solver's rounding)
  // Both solve the same problem to 1e-12; grains move at ~0.3 m/s.
  EXPECT_LT(largest_difference(on_many.vx, on_one.vx), 1e-9);
  EXPECT_LT(largest_difference(on_many.vy, on_one.vy), 1e-9);
}

// Conjugate acceleration on several ranks (each takes beta from the change summed over all
// ranks) reaches the 1-rank solution of the same step.
TEST_F(SeveralRanks, ConjugateAccelerationGivesTheSameVelocities)
{
  expect_one_rank_velocities("acceleration conjugate");
}

// Cycles that skip quiet contacts between full sweeps (full_sweep_every): every rank takes the
// same full and active sweeps, since the choice depends only on norms summed over ranks.
TEST_F(SeveralRanks, CyclesOfActiveSweepsGiveTheSameVelocities)
{
  expect_one_rank_velocities("acceleration conjugate full_sweep_every 8");
}

// Over-relaxation on several ranks: every rank over-relaxes after the same sweeps, those in which
// no contact of any rank changed its law's face (the count summed over ranks), and the solve
// reaches the 1-rank solution.
TEST_F(SeveralRanks, OverRelaxationGivesTheSameVelocities)
{
  expect_one_rank_velocities("over_relaxation 1.8 full_sweep_every 8");
}

// The stall rescue made to act at the end of every window of two sweeps (a coherence that only
// sweeps changing nothing would pass): each rank decides on the net change and path summed over
// all ranks, solves the blocks around its own contacts' residual and shares the velocities they
// change; the solve reaches the 1-rank solution.
TEST_F(SeveralRanks, AStallRescueReachesTheOneRankSolution)
{
  expect_one_rank_velocities("stall_window 2 stall_coherence 0.999999");
}

// The same with the kept block solved again two sweeps after each block: every rank solves its
// own at once and shares the velocities. Before the block solve put Lemke's answer on the cone,
// 2 ranks held the norm at 5e-9 to the cap of 1e5 sweeps (a round-off tangential impulse
// on an open contact, taken off by the sweeps and put back by the next solve); now 66 sweeps, 1
// rank 86.
TEST_F(SeveralRanks, AKeptBlockReachesTheOneRankSolution)
{
  expect_one_rank_velocities("stall_window 4 stall_coherence 0.999999 stall_block_every 2");
  if (world_rank() != 0) return;
  EXPECT_LT(on_many.sweeps, 1000);
  EXPECT_LT(on_one.sweeps, 1000);
}

// The same with the rescue's restarts from zero impulses instead of block solves.
TEST_F(SeveralRanks, AStallRescueByRestartsReachesTheOneRankSolution)
{
  expect_one_rank_velocities("stall_window 2 stall_coherence 0.999999 stall_block 0");
}

// Over 100 steps of landing grains, collisions amplify the solver differences by a few
// orders; a wrong interface impulse would show at ~1e-3 d. The solve is tight (tight_solve) because
// the impact test of the normal law is a switch: at 1e-10 one pair (step 97 of the balance
// case) sits 2e-8 d from it on 1 rank, 4 ranks put its impact one step earlier, and the
// trajectories part by (1 + e) |u_n| dt = 1e-4 d with no defect in the decomposition (1 rank
// at 1e-10 against 1 rank at 1e-12 shows the same 1e-4 d).
constexpr double trajectory_tolerance = 1e-6;  // in d

TEST_F(SeveralRanks, ShortTrajectoriesAgreeToSolverTolerance)
{
  run_both(tight_solve, "run 100");
  if (world_rank() != 0) return;
  EXPECT_LT(largest_difference(on_many.x, on_one.x, 20 * d) / d, trajectory_tolerance);
  EXPECT_LT(largest_difference(on_many.y, on_one.y) / d, trajectory_tolerance);
}

// A floor region rising under the landed grains (a plane region moving with a variable of time)
// carries them across both ranks as on one: region walls are met by each rank's own grains.
TEST_F(SeveralRanks, ARisingRegionFloorGivesTheOneRankTrajectory)
{
  run_both(std::string(tight_solve) + " wall region lift 0.5 0.5",
           "variable rise equal 0.05*time\nregion lift plane 0 0 0 0 1 0 side in units box move NULL v_rise NULL\n"
           "run 100");
  if (world_rank() != 0) return;
  EXPECT_LT(largest_difference(on_many.x, on_one.x, 20 * d) / d, trajectory_tolerance);
  EXPECT_LT(largest_difference(on_many.y, on_one.y) / d, trajectory_tolerance);
}

TEST_F(SeveralRanks, LoadBalancingKeepsTheTrajectory)
{
  // fix balance moves the cut between the ranks every 20 steps; atoms migrate with their
  // warm-start rows.
  run_both(tight_solve, "fix lb all balance 20 1.0 shift x 5 1.05\nrun 100");
  if (world_rank() != 0) return;
  EXPECT_LT(largest_difference(on_many.x, on_one.x, 20 * d) / d, trajectory_tolerance);
  EXPECT_LT(largest_difference(on_many.y, on_one.y) / d, trajectory_tolerance);
}

TEST_F(SeveralRanks, SameRankCountIsBitwiseReproducible)
{
  State first, second;
  for (State* target : {&first, &second}) {
    LammpsSession many(MPI_COMM_WORLD);
    load(many, "tolerance 1e-4");
    many.commands("run 200");
    *target = state_of(many);
  }
  EXPECT_EQ(first.x, second.x);
  EXPECT_EQ(first.y, second.y);
  EXPECT_EQ(first.vx, second.vx);
}

TEST_F(SeveralRanks, RestartWrittenOnSeveralRanksContinuesOnOne)
{
  const std::string restart = "test_mpi.restart", unbroken = "test_mpi.unbroken", restarted = "test_mpi.restarted";
  const std::string options = "tolerance 1e-10 max_iterations 100000";
  {
    LammpsSession many(MPI_COMM_WORLD);
    load(many, options);
    many.commands("run 100\nwrite_restart " + restart);
    many.commands("fix iters all ave/time 1 1 1 f_cd[1] file " + unbroken + "\nrun 20\nunfix iters");
    on_many = state_of(many);
  }
  if (world_rank() != 0) return;
  LammpsSession one(MPI_COMM_SELF);
  one.commands("read_restart " + restart);
  one.commands(cdtest::small_deposition_after_restart(options));
  one.commands("fix iters all ave/time 1 1 1 f_cd[1] file " + restarted + "\nrun 20\nunfix iters");
  on_one = state_of(one);
  const std::vector<double> before = cdtest::ave_time_values_after(unbroken, 100);
  const std::vector<double> after = cdtest::ave_time_values_after(restarted, 100);
  ASSERT_EQ(before.size(), 20u);
  ASSERT_EQ(after.size(), 20u);
  EXPECT_LT(largest_difference(on_many.x, on_one.x, 20 * d) / d, trajectory_tolerance);
  for (const std::string& file : {restart, unbroken, restarted}) std::remove(file.c_str());
}

// The warm start across a change of rank count, where it shows: four resting columns of ten
// disks, one or two per rank, written on every rank and continued on one. Restored, the first
// step after the restart takes the sweeps of the unbroken run's; lost, many more (each
// column's weight carried from zero). The falling packing of the test above cannot tell: a
// cold start there takes about the sweeps of a warm one.
struct ColumnSweeps {
  double unbroken = 0.0, restarted = 0.0;
};

ColumnSweeps first_step_sweeps_after_columns_restart(const std::string& fix_options)
{
  ColumnSweeps sweeps;
  const std::string restart = "test_mpi_columns.restart";
  const std::string fix_line =
      "fix cd all contact/dynamics 0.5 0.5 wall yplane 0.0 0.5 0.5 tolerance 1e-10 max_iterations 100000 ";
  const std::string physics = fmt::format("neighbor {} bin\nfix grav all gravity 9.81 vector 0 -1 0\n", 0.2 * d);
  {
    LammpsSession many(MPI_COMM_WORLD);
    many.commands(cdtest::disk_preamble);
    many.commands(fmt::format("boundary p f p\nregion box block 0 {L} 0 {L} -{r} {r}\ncreate_box 1 box",
                              fmt::arg("L", 20 * d), fmt::arg("r", 0.6 * d)));
    for (int column = 0; column < 4; column++)
      for (int k = 0; k < 10; k++)
        many.commands(fmt::format("create_atoms 1 single {} {} 0", (5 * column + 2.5) * d, (k + 0.5) * d));
    many.commands(fmt::format("set group all diameter {} density/disc 2500\ntimestep 1e-5\n", d) + physics + fix_line +
                  "\nfix 2d all enforce2d\nrun 100\nwrite_restart " + restart + "\nrun 1");
    sweeps.unbroken = many.fix("cd")->compute_vector(0);
  }
  if (world_rank() != 0) return sweeps;
  LammpsSession one(MPI_COMM_SELF);
  one.commands("read_restart " + restart + "\ncomm_modify vel yes\nneigh_modify delay 0 every 1 check yes\n" + physics +
               fix_line + fix_options + "\nfix 2d all enforce2d\nrun 1");
  sweeps.restarted = one.fix("cd")->compute_vector(0);
  std::remove(restart.c_str());
  return sweeps;
}

TEST(SeveralRanksRestart, RestoredWarmStartSolvesRestingColumnsAsUnbroken)
{
  const ColumnSweeps sweeps = first_step_sweeps_after_columns_restart("");
  if (world_rank() != 0) return;
  EXPECT_LE(sweeps.restarted, sweeps.unbroken + 1.0);
}

TEST(SeveralRanksRestart, ColdStartNeedsManySweeps)
{
  // The same check fails without the restored impulses.
  const ColumnSweeps sweeps = first_step_sweeps_after_columns_restart("warm_start no");
  if (world_rank() != 0) return;
  EXPECT_GT(sweeps.restarted, 4.0 * sweeps.unbroken);
}

// Two disks meeting head on through the periodic boundary, owned by the first and the last rank.
TEST(SeveralRanksAnalytic, ImpactBetweenRanksFollowsNewtonRestitution)
{
  LammpsSession s(MPI_COMM_WORLD);
  s.commands(cdtest::disk_preamble);
  const double v = 0.2, e = 0.5;
  s.commands(cdtest::periodic_impact_deck(d, v, e, "processors * 1 1"));
  const auto* atom = s.lmp->atom;
  const std::vector<double> vx = by_id(s, [&](int i) { return atom->v[i][0]; });
  const std::vector<double> owner = by_id(s, [&](int) { return static_cast<double>(world_rank()); });
  EXPECT_NE(owner[0], owner[1]) << "the disks must sit on different ranks";
  EXPECT_NEAR(vx[0], v * (1 - e) / 2, 1e-12);
  EXPECT_NEAR(vx[1], v * (1 + e) / 2, 1e-12);
  EXPECT_EQ(s.fix("cd")->compute_vector(2), 1.0) << "the pair is solved once over both ranks";
}

}  // namespace
