// Deck-level tests of reference/: a small chute (8 d, 40 grains, walls 3 d) run briefly in
// LAMMPS GRANULAR (Hooke and Hertz), LIGGGHTS and, when lmp_cd is built, the rigid model, all
// from one rain; the binary-collision decks on the chute decks' own parameters; and
// `cdref compare` on those runs. The runs are made once, in SetUpTestSuite.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>

#include "collision.h"
#include "io/ave_chunk.h"
#include "io/ave_time.h"
#include "io/dump.h"
#include "run_info.h"
#include "scratch.h"
#include "spatial_to_chunk.h"

namespace fs = std::filesystem;
using cdref::testing::read_file;

namespace {

const std::string reference_dir = CDREF_REFERENCE_DIR;
const std::string lmp = LMP_EXECUTABLE;
const std::string liggghts = LIGGGHTS_EXECUTABLE;
const std::string lmp_cd = LMP_CD_EXECUTABLE;
const std::string cdref_exe = CDREF_EXECUTABLE;

constexpr double kD = 5e-4;
constexpr int kGrains = 40;
constexpr int kWallGrains = 6;  // 3 d of wall grains of 0.5 d
const std::string kSmall = " -var bed_walls 3 -var settle 0.03 -var flow 0.1 -var sample_max 2e-4 -var dump_every 0.02";

int run_in(const fs::path& dir, const std::string& command)
{
  fs::create_directories(dir);
  const std::string line = "cd '" + dir.string() + "' && " + command + " > screen.txt 2>&1";
  return std::system(line.c_str());
}

class ReferenceDecks : public ::testing::Test {
 protected:
  static fs::path root;
  static std::map<std::string, int> status;  // run name -> exit status (absent: not run)

  static void SetUpTestSuite()
  {
    root = cdref::testing::scratch_dir("decks");
    status["rain"] =
        run_in(root, lmp + " -in " + reference_dir + "/in.rain -log none -var out rain.data -var cells 8 -var grains " +
                         std::to_string(kGrains) + " -var bed_walls 3");
    if (status["rain"] != 0) return;
    const std::string data = " -var data ../rain.data";
    status["granular-hooke"] =
        run_in(root / "granular-hooke", lmp + " -in " + reference_dir + "/in.chute_granular -log log.lammps" + data +
                                            kSmall + " -var model hooke -var overlap 1e-2");
    status["granular-hertz"] =
        run_in(root / "granular-hertz", lmp + " -in " + reference_dir + "/in.chute_granular -log log.lammps" + data +
                                            kSmall + " -var model hertz -var overlap 1e-2");
    if (!liggghts.empty())
      status["liggghts"] =
          run_in(root / "liggghts", "stdbuf -o0 " + liggghts + " -in " + reference_dir +
                                        "/in.chute_liggghts -log log.liggghts" + data + kSmall + " -var overlap 1e-2");
    if (!lmp_cd.empty())
      status["rigid"] = run_in(root / "rigid", lmp_cd + " -in " + reference_dir + "/in.chute_rigid -log log.lammps" +
                                                   data + kSmall + " -var tolerance 1e-2");
  }

  static void require(const std::string& name)
  {
    if (name == "liggghts" && liggghts.empty()) GTEST_SKIP() << "liggghts not installed";
    if (name == "rigid" && lmp_cd.empty()) GTEST_SKIP() << "lmp_cd not built";
    ASSERT_EQ(status.at(name), 0) << name << " failed: " << read_file(root / name / "screen.txt");
  }
};
fs::path ReferenceDecks::root;
// Stops the calling test when `name` did not run (skipped, or failed with its screen output).
#define REQUIRE_RUN(name)                         \
  do {                                            \
    require(name);                                \
    if (HasFatalFailure() || IsSkipped()) return; \
  } while (0)
std::map<std::string, int> ReferenceDecks::status;

// The files of doc/postproc_method.md, with sane contents: every grain kept, wall grains unmoved,
// the flowing layer moving downhill.
void check_chute_outputs(const fs::path& dir, const std::string& code)
{
  auto info = cdref::read_run_info((dir / "run.info").string());
  EXPECT_EQ(info.text("code").value_or(""), code);
  EXPECT_EQ(info.number("grains").value_or(0), kGrains);
  auto flow = cdpost::read_ave_time((dir / "flow.time").string());
  for (const char* column : {"v_u_all", "v_u_flow", "v_v_flow", "v_phi_flow", "v_h"})
    EXPECT_TRUE(flow.has(column)) << column;
  const double samples = 0.1 / info.number("sample_interval").value();
  EXPECT_NEAR(static_cast<double>(flow.rows()), samples, 2);
  const auto& u = flow.column("v_u_flow");
  double late = 0;
  for (size_t i = u.size() / 2; i < u.size(); ++i) late += u[i];
  EXPECT_GT(late, 0) << "the layer above the walls flows along +x";
  EXPECT_NO_THROW(cdpost::read_ave_chunk((dir / "layers.chunk").string()));

  cdpost::DumpReader dump((dir / "dump.chute").string());
  cdpost::DumpFrame frame;
  int frames = 0;
  while (dump.next(frame)) {
    ++frames;
    ASSERT_EQ(frame.atoms, static_cast<size_t>(kGrains + kWallGrains));
    const size_t type = frame.column_index("type"), x = frame.column_index("x"), y = frame.column_index("y");
    for (size_t a = 0; a < frame.atoms; ++a)
      if (frame.value(a, type) == 2) {
        EXPECT_DOUBLE_EQ(frame.value(a, x), 0.0);
        EXPECT_LT(frame.value(a, y), 3 * kD);
      } else {
        EXPECT_GT(frame.value(a, y), 0.3 * kD) << "a grain is in the floor";
      }
  }
  EXPECT_GE(frames, 5);
}

cdref::CollisionResult collide(const fs::path& dir, const std::string& command)
{
  EXPECT_EQ(run_in(dir, command), 0) << read_file(dir / "screen.txt");
  return cdref::analyse_collision((dir / "collision.txt").string());
}

}  // namespace

TEST_F(ReferenceDecks, RainHoldsTheGrainsAndTheWallColumn)
{
  REQUIRE_RUN("rain");
  const auto text = read_file(root / "rain.data");
  EXPECT_NE(text.find(std::to_string(kGrains + kWallGrains) + " atoms"), std::string::npos);
  EXPECT_NE(text.find("2 atom types"), std::string::npos);
}

TEST_F(ReferenceDecks, LammpsGranularHookeChute)
{
  REQUIRE_RUN("granular-hooke");
  check_chute_outputs(root / "granular-hooke", "lammps-granular");
  EXPECT_NO_THROW(cdpost::read_ave_chunk((root / "granular-hooke" / "profile.chunk").string()));
}

// The samples of a flow continued in `part` go on one interval after those of `first`'s last
// one, for 0.05 s, from the same state (the layer's velocity changes little in one interval).
// `clock` is the flow.time column that counts time, `seconds` its unit in s.
void expect_continued(const fs::path& first_dir, const fs::path& part, const std::string& clock, double seconds)
{
  const auto first = cdpost::read_ave_time((first_dir / "flow.time").string());
  const auto second = cdpost::read_ave_time((part / "flow.time").string());
  ASSERT_GT(first.rows(), 2u);
  ASSERT_GT(second.rows(), 2u);
  const auto& t1 = first.column(clock);
  const auto& t2 = second.column(clock);
  const double interval = t1[t1.size() - 1] - t1[t1.size() - 2];
  EXPECT_NEAR(t2[0] - t1.back(), interval, 1e-3 * interval);
  EXPECT_NEAR((t2.back() - t1.back()) * seconds, 0.05, 2 * interval * seconds);
  const auto& u1 = first.column("v_u_flow");
  const auto& u2 = second.column("v_u_flow");
  EXPECT_NEAR(u2[0], u1.back(), 0.05 * std::abs(u1.back()) + 1e-4);
}

// A flow continued in a second part from the first part's flow.restart (run_comparison.sh
// --soft-parts): the samples go on one interval after the first part's last, from the same
// state (the layer's velocity changes little in one interval), with no warning.
TEST_F(ReferenceDecks, LammpsGranularFlowContinuesInParts)
{
  REQUIRE_RUN("granular-hooke");
  const fs::path part = root / "granular-hooke" / "part2";
  ASSERT_EQ(run_in(part, lmp + " -in " + reference_dir +
                             "/in.chute_granular -log log.lammps -var part 2 -var restart_in ../flow.restart"
                             " -var bed_walls 3 -var flow 0.05 -var sample_max 2e-4 -var dump_every 0.02"
                             " -var model hooke -var overlap 1e-2"),
            0)
      << read_file(part / "screen.txt");
  EXPECT_EQ(read_file(part / "screen.txt").find("WARNING"), std::string::npos);
  expect_continued(root / "granular-hooke", part, "v_time", 1.0);
}

// The same for LIGGGHTS (flow.time has no time column: TimeStep x dt). The warnings of fix
// check/timestep/gran, which compares the step with Hertz and Rayleigh times, are the first
// part's as well.
TEST_F(ReferenceDecks, LiggghtsFlowContinuesInParts)
{
  REQUIRE_RUN("liggghts");
  const fs::path part = root / "liggghts" / "part2";
  ASSERT_EQ(run_in(part, "stdbuf -o0 " + liggghts + " -in " + reference_dir +
                             "/in.chute_liggghts -log log.liggghts -var part 2 -var restart_in ../flow.restart"
                             " -var bed_walls 3 -var flow 0.05 -var sample_max 2e-4 -var dump_every 0.02"
                             " -var overlap 1e-2"),
            0)
      << read_file(part / "screen.txt");
  const double dt = *cdref::read_run_info((root / "liggghts" / "run.info").string()).number("dt");
  expect_continued(root / "liggghts", part, "TimeStep", dt);
}

TEST_F(ReferenceDecks, LammpsGranularHertzChute)
{
  REQUIRE_RUN("granular-hertz");
  check_chute_outputs(root / "granular-hertz", "lammps-granular");
}

TEST_F(ReferenceDecks, LiggghtsChuteAndItsConvertedChunks)
{
  REQUIRE_RUN("liggghts");
  const auto dir = root / "liggghts";
  for (const char* f : {"profile", "layers"})
    cdref::spatial_to_chunk((dir / (std::string(f) + ".spatial")).string(),
                            (dir / (std::string(f) + ".chunk")).string());
  check_chute_outputs(dir, "liggghts");
}

TEST_F(ReferenceDecks, RigidCounterpart)
{
  REQUIRE_RUN("rigid");
  check_chute_outputs(root / "rigid", "lmp_cd");
}

// The damping gives e = 0.5 and the time step resolves the lightest pair's contact in about
// steps_per_contact = 50 steps, with each chute deck's own parameters.
TEST_F(ReferenceDecks, CollisionsCheckRestitutionAndTimeStep)
{
  REQUIRE_RUN("granular-hooke");
  auto info = cdref::read_run_info((root / "granular-hooke" / "run.info").string());
  const std::string args =
      " -var kn " + *info.text("k_n") + " -var eT " + *info.text("e_tsuji") + " -var dt " + *info.text("dt");
  auto light =
      collide(root / "collision-hooke", lmp + " -in " + reference_dir + "/in.collision_granular -log none" + args);
  EXPECT_NEAR(light.restitution, 0.5, 0.015);
  EXPECT_GE(light.contact_steps, 48);
  auto mean = collide(root / "collision-hooke-d", lmp + " -in " + reference_dir + "/in.collision_granular -log none" +
                                                      args + " -var d1 1 -var d2 1");
  EXPECT_NEAR(mean.restitution, 0.5, 0.015);

  REQUIRE_RUN("granular-hertz");
  info = cdref::read_run_info((root / "granular-hertz" / "run.info").string());
  auto hertz =
      collide(root / "collision-hertz",
              lmp + " -in " + reference_dir + "/in.collision_granular -log none -var model hertz" + " -var kn " +
                  *info.text("k_n") + " -var eT " + *info.text("e_tsuji") + " -var dt " + *info.text("dt"));
  EXPECT_NEAR(hertz.restitution, 0.5, 0.015);
  EXPECT_GE(hertz.contact_steps, 45) << "at the impact speed v_ref = 1 m/s";

  REQUIRE_RUN("liggghts");
  info = cdref::read_run_info((root / "liggghts" / "run.info").string());
  const std::string largs = " -var Y " + *info.text("youngs_modulus") + " -var dt " + *info.text("dt");
  auto lig = collide(root / "collision-liggghts",
                     "stdbuf -o0 " + liggghts + " -in " + reference_dir + "/in.collision_liggghts -log none" + largs);
  EXPECT_NEAR(lig.restitution, 0.5, 0.015);
  EXPECT_GE(lig.contact_steps, 50) << "LIGGGHTS's k_n of the lightest pair is below k";
  auto lig_mean =
      collide(root / "collision-liggghts-d", "stdbuf -o0 " + liggghts + " -in " + reference_dir +
                                                 "/in.collision_liggghts -log none" + largs + " -var d1 1 -var d2 1");
  auto granular_mean = mean;
  EXPECT_NEAR(lig_mean.contact_steps, granular_mean.contact_steps, 1)
      << "Y is calibrated so that the mean pair has the same k";
}

TEST_F(ReferenceDecks, CompareTheSmallRuns)
{
  REQUIRE_RUN("granular-hooke");
  REQUIRE_RUN("granular-hertz");
  std::string dirs = " granular-hooke granular-hertz";
  if (!liggghts.empty() && status["liggghts"] == 0) {
    for (const char* f : {"profile", "layers"})
      cdref::spatial_to_chunk((root / "liggghts" / (std::string(f) + ".spatial")).string(),
                              (root / "liggghts" / (std::string(f) + ".chunk")).string());
    dirs += " liggghts";
  }
  if (!lmp_cd.empty() && status["rigid"] == 0) dirs += " rigid";
  ASSERT_EQ(run_in(root, cdref_exe + " compare" + dirs + " --out comparison --segment 0.02 --t-start 0.05"), 0)
      << read_file(root / "screen.txt");
  const auto table = read_file(root / "comparison" / "table.csv");
  EXPECT_NE(table.find("granular hooke 1e-2"), std::string::npos) << table;
  EXPECT_NE(table.find("granular hertz 1e-2"), std::string::npos) << table;
  EXPECT_TRUE(fs::exists(root / "comparison" / "report.md"));
  EXPECT_TRUE(fs::exists(root / "comparison" / "figures" / "spectra.gp"));
}
