// A small deposition settles without interpenetration; a restart continues it seamlessly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "domain.h"
#include "variable.h"
#include "lammps_session.h"
#include "shared_decks.h"
#include "small_deposition.h"

namespace {

using cdtest::LammpsSession;
constexpr double d = cdtest::deposition_d;

// Deepest overlap over all pairs, from positions and radii alone (x-periodic minimum image),
// in mean diameters: independent of the fix's own bookkeeping.
double deepest_overlap(const LammpsSession& s)
{
  const auto* atom = s.lmp->atom;
  const double length = s.lmp->domain->xprd;
  double deepest = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    for (int j = i + 1; j < atom->nlocal; j++) {
      double dx = atom->x[i][0] - atom->x[j][0];
      dx -= length * std::nearbyint(dx / length);
      const double dy = atom->x[i][1] - atom->x[j][1];
      const double overlap = atom->radius[i] + atom->radius[j] - std::hypot(dx, dy);
      deepest = std::max(deepest, overlap);
    }
  for (int i = 0; i < atom->nlocal; i++) deepest = std::max(deepest, atom->radius[i] - atom->x[i][1]);
  return deepest / d;
}

double kinetic_energy_per_grain(LammpsSession& s)
{
  s.commands("variable ke equal ke/atoms");
  return s.lmp->input->variable->compute_equal("v_ke");
}

TEST(Deposition, SettlesWithoutInterpenetration)
{
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  s.commands(cdtest::small_deposition(4711, "tolerance 1e-4"));
  s.commands("run 30000");  // 0.3 s: the last grains land after ~0.1 s
  // Settled: kinetic energy per grain below that of a fall of 1e-4 d.
  const double grain_mass = M_PI * 0.25 * d * d * 2500.0;
  EXPECT_LT(kinetic_energy_per_grain(s), grain_mass * 9.81 * 1e-4 * d);
  // Rigid grains: the overlap left by an unconverged step (tolerance 1e-4) stays below 1e-3 d.
  const double overlap = deepest_overlap(s);
  EXPECT_LT(overlap, 1e-3);
  // The fix's own measure (output 5, over the pairs and walls its last step looked at) agrees.
  EXPECT_NEAR(s.fix("cd")->compute_vector(4), overlap, 1e-5);
}

constexpr int restart_step = 4000;

struct Snapshot {
  std::vector<double> x, y;
};

Snapshot positions_by_id(const LammpsSession& s)
{
  Snapshot snap;
  for (int id = 1; id <= static_cast<int>(s.lmp->atom->natoms); id++) {
    snap.x.push_back(s.x(id, 0));
    snap.y.push_back(s.x(id, 1));
  }
  return snap;
}

class Restart : public ::testing::Test {
 protected:
  void SetUp() override
  {
    LammpsSession unbroken;
    unbroken.commands(cdtest::disk_preamble);
    unbroken.commands(cdtest::small_deposition(99, "tolerance 1e-10 max_iterations 100000"));
    unbroken.commands(fmt::format("run {}", restart_step));  // grains piling up: many contacts
    unbroken.commands("write_restart " + restart_file);
    unbroken.commands("fix iters all ave/time 1 1 1 f_cd[1] file " + unbroken_iterations);
    unbroken.commands("run 100");
    reference = positions_by_id(unbroken);
  }
  void TearDown() override
  {
    std::remove(restart_file.c_str());
    std::remove(unbroken_iterations.c_str());
    std::remove(restarted_iterations.c_str());
  }

  Snapshot restarted_run(const std::string& fix_options)
  {
    LammpsSession s;
    s.commands("read_restart " + restart_file);
    s.commands(cdtest::small_deposition_after_restart("tolerance 1e-10 max_iterations 100000 " + fix_options));
    s.commands("fix iters all ave/time 1 1 1 f_cd[1] file " + restarted_iterations + "\nrun 100");
    return positions_by_id(s);
  }

  // Per-test file names: ctest may run the tests of this fixture in parallel.
  const std::string prefix =
      std::string("test_restart_") + ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string restart_file = prefix + ".restart";
  const std::string unbroken_iterations = prefix + ".unbroken.txt";
  const std::string restarted_iterations = prefix + ".restarted.txt";
  Snapshot reference;
};

TEST_F(Restart, ContinuesTheUnbrokenRunWithItsWarmStart)
{
  const Snapshot restarted = restarted_run("");
  const std::vector<double> before = cdtest::ave_time_values_after(unbroken_iterations, restart_step);
  const std::vector<double> after = cdtest::ave_time_values_after(restarted_iterations, restart_step);
  ASSERT_EQ(before.size(), 100u);
  ASSERT_EQ(after.size(), 100u);
  // The warm start survives: the first steps need no more iterations than unbroken (the
  // contact order may differ after reading the restart, hence a margin of a few sweeps).
  for (int step = 0; step < 3; step++) EXPECT_LE(after[step], before[step] + 3) << "step " << step;
  // Trajectories agree to solver tolerance over 100 steps (1 ms).
  double largest = 0.0;
  for (std::size_t k = 0; k < reference.x.size(); k++)
    largest = std::max(largest, std::hypot(restarted.x[k] - reference.x[k], restarted.y[k] - reference.y[k]));
  EXPECT_LT(largest / d, 1e-7);
}

// A resting column is where the warm start shows most: restored, it solves the first step
// after the restart in a sweep or two; lost, the step needs many sweeps to carry the weight.
// Sweeps of the first step after the restart, and of the same step in the unbroken run.
struct ColumnSweeps {
  double restarted, unbroken;
};

ColumnSweeps first_step_sweeps_after_column_restart(const std::string& fix_options)
{
  ColumnSweeps sweeps{};
  const std::string restart = "test_restart_column_" + std::to_string(fix_options.size()) + ".restart";
  const std::string fix_line =
      "fix cd all contact/dynamics 0.5 0.5 wall yplane 0.0 0.5 0.5 tolerance 1e-10 max_iterations 100000 ";
  {
    LammpsSession s;
    s.commands(cdtest::disk_preamble);
    s.commands(fmt::format("boundary p f p\nregion box block 0 {L} 0 {L} -{r} {r}\ncreate_box 1 box",
                           fmt::arg("L", 20 * d), fmt::arg("r", 0.6 * d)));
    for (int k = 0; k < 10; k++) s.commands(fmt::format("create_atoms 1 single {} {} 0", 10 * d, 0.5 * d + k * d));
    s.commands(fmt::format("set group all diameter {d} density/disc 2500\nneighbor {skin} bin\ntimestep 1e-5\n"
                           "fix grav all gravity 9.81 vector 0 -1 0\n",
                           fmt::arg("d", d), fmt::arg("skin", 0.2 * d)) +
               fix_line + "\nfix 2d all enforce2d\nrun 100\nwrite_restart " + restart + "\nrun 1");
    sweeps.unbroken = s.fix("cd")->compute_vector(0);
  }
  LammpsSession s;
  s.commands("read_restart " + restart);
  s.commands(fmt::format("neighbor {} bin\ncomm_modify vel yes\nneigh_modify delay 0 every 1 check yes\n"
                         "fix grav all gravity 9.81 vector 0 -1 0\n",
                         0.2 * d) +
             fix_line + fix_options + "\nfix 2d all enforce2d\nrun 1");
  std::remove(restart.c_str());
  sweeps.restarted = s.fix("cd")->compute_vector(0);
  return sweeps;
}

TEST(RestartWarmStart, RestoredWarmStartSolvesARestingColumnAsUnbroken)
{
  const ColumnSweeps sweeps = first_step_sweeps_after_column_restart("");
  EXPECT_LE(sweeps.restarted, sweeps.unbroken + 1.0);
}

TEST(RestartWarmStart, ColdStartNeedsManySweeps)
{
  // The same check fails without the restored impulses.
  const ColumnSweeps sweeps = first_step_sweeps_after_column_restart("warm_start no");
  EXPECT_GT(sweeps.restarted, 4.0 * sweeps.unbroken);
}

}  // namespace
