// What a run reproduces bit for bit on one rank: a run split at a restart file continues as
// the same run split in one instance (the case doc/fix_contact_dynamics.rst states).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "lammps_session.h"
#include "small_deposition.h"

namespace {

using cdtest::LammpsSession;
constexpr int half_run = 3000;  // steps: the grains of the small deposition land and pile up
const std::string tolerance = "tolerance 1e-4";

// Every atom's state by ID, and the fix's running totals (outputs 8-10).
struct RunState {
  std::vector<double> x, y, vx, vy, spin;
  std::vector<double> totals;
};

RunState state_of(const LammpsSession& s)
{
  RunState st;
  for (int id = 1; id <= static_cast<int>(s.lmp->atom->natoms); id++) {
    st.x.push_back(s.x(id, 0));
    st.y.push_back(s.x(id, 1));
    st.vx.push_back(s.v(id, 0));
    st.vy.push_back(s.v(id, 1));
    st.spin.push_back(s.spin(id));
  }
  for (int k = 7; k <= 9; k++) st.totals.push_back(s.fix("cd")->compute_vector(k));
  return st;
}

void expect_bitwise_equal(const RunState& a, const RunState& b)
{
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vy, b.vy);
  EXPECT_EQ(a.spin, b.spin);
  EXPECT_EQ(a.totals, b.totals);
}

// `run N` + write_restart + (a new instance) read_restart + `run N` gives exactly the state of
// `run N; run N` in one instance: positions, velocities, spins, warm starts (through the
// solution) and the running totals. Both take a run's setup (neighbour lists and atom order
// rebuilt) at step N; an unbroken `run 2N` does not, and rounding differences that setup makes
// grow in a pile, so it is not reproduced.
TEST(Reproducibility, RunSplitAtARestartIsBitwiseTheSameAsTwoRuns)
{
  const std::string restart = "test_reproducibility.restart";
  RunState in_one_instance, through_the_file;
  {
    LammpsSession s;
    s.commands(cdtest::disk_preamble);
    s.commands(cdtest::small_deposition(99, tolerance));
    s.commands(fmt::format("run {}\nwrite_restart {}\nrun {}", half_run, restart, half_run));
    in_one_instance = state_of(s);
  }
  {
    LammpsSession s;
    s.commands("read_restart " + restart);
    s.commands(cdtest::small_deposition_after_restart(tolerance));
    s.commands(fmt::format("run {}", half_run));
    through_the_file = state_of(s);
  }
  std::remove(restart.c_str());
  EXPECT_EQ(in_one_instance.totals[2], 2.0 * half_run);  // steps solved, kept across the restart
  expect_bitwise_equal(in_one_instance, through_the_file);
}

// Writing the restart file does not disturb the run that wrote it: `run N; run N` with and
// without a write_restart between the runs give the same state.
TEST(Reproducibility, WritingARestartLeavesTheRunAsItWas)
{
  const std::string restart = "test_reproducibility_written.restart";
  std::vector<RunState> states;
  for (const std::string between : {"write_restart " + restart, std::string()}) {
    LammpsSession s;
    s.commands(cdtest::disk_preamble);
    s.commands(cdtest::small_deposition(99, tolerance));
    s.commands(fmt::format("run {}\n{}\nrun {}", half_run, between, half_run));
    states.push_back(state_of(s));
  }
  std::remove(restart.c_str());
  expect_bitwise_equal(states[0], states[1]);
}

}  // namespace
