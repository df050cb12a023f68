// The shipped examples of inputs/examples/ keep running: LAMMPS's 2D pour, rigid and soft, on
// shortened runs in a scratch folder (no ERROR or WARNING, every batch poured, the grains in the
// box, the rigid contacts' overlaps within what the full run met), the 2D silo, rigid and soft,
// and the plane shear of a Lees-Edwards cell (its stress tensor against torque balance, its shear
// rate from the profile).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#ifndef EXAMPLES_DIR
#error "EXAMPLES_DIR must name inputs/examples"
#endif

namespace {

struct ExampleRun {
  int exit_status;
  std::string output;
  std::filesystem::path folder;
};

ExampleRun run_example(const std::string& deck, const std::string& variables)
{
  const auto folder = std::filesystem::temp_directory_path() / ("cd_example_" + deck + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(folder);
  const std::string command = "cd " + folder.string() + " && " LMP_CD_EXECUTABLE " -log none -in " EXAMPLES_DIR "/" +
                              deck + " " + variables + " 2>&1";
  ExampleRun run{0, "", folder};
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  run.exit_status = pclose(pipe);
  return run;
}

// The value after `key` on the last line of the output that starts with `prefix` (a deck's
// closing "POUR ..." line, its "FUNNEL drained ..." line); -1 without one.
double printed_value(const std::string& output, const std::string& prefix, const std::string& key)
{
  const auto line = output.rfind("\n" + prefix + " ");
  if (line == std::string::npos) return -1;
  const auto start = line + prefix.size() + 2;
  std::istringstream words(output.substr(start, output.find('\n', start) - start));
  std::string word;
  double value = -1;
  while (words >> word)
    if (word == key && words >> value) return value;
  return -1;
}

double pour_value(const std::string& output, const std::string& key)
{
  return printed_value(output, "POUR", key);
}

// Every grain of pour.final inside the box 0 < x < 100 above the floor y = 0 (centre one radius in).
void expect_in_the_box(const std::filesystem::path& final_frame, double tolerance)
{
  std::ifstream in(final_frame);
  std::string line;
  while (std::getline(in, line) && line.rfind("ITEM: ATOMS", 0) != 0) {
  }
  double id, x, y, vx, vy, r;
  int grains = 0;
  while (in >> id >> x >> y >> vx >> vy >> r) {
    ++grains;
    EXPECT_GT(x - r, -tolerance) << "grain " << id;
    EXPECT_LT(x + r, 100 + tolerance) << "grain " << id;
    EXPECT_GT(y - r, -tolerance) << "grain " << id;
  }
  EXPECT_GT(grains, 0);
}

void expect_clean(const ExampleRun& run)
{
  ASSERT_EQ(run.exit_status, 0) << run.output.substr(run.output.size() > 2000 ? run.output.size() - 2000 : 0);
  EXPECT_EQ(run.output.find("ERROR"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("WARNING"), std::string::npos) << run.output;
}

TEST(PourExample, RigidPoursEveryBatchWithoutOverlap)
{
  // 11 time units: batches of 224 at t = 0, 3, 6 and 9, the first ones landed (from t ~ 5).
  const auto run = run_example("in.pour_rigid", "-var duration 11");
  expect_clean(run);
  EXPECT_EQ(pour_value(run.output, "grains"), 4 * 224);
  EXPECT_EQ(pour_value(run.output, "capped"), 0);
  // f_cd[5], the largest interpenetration at each thermo step (in mean diameters): at most about
  // 0.02 d, as the first grains land at 8 sqrt(g d) (below 5e-4 d once the pile rests); twice that
  // may be met between samples.
  std::istringstream lines(run.output);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    std::istringstream row(line);
    double step, time, atoms, ke, sweeps, overlap;
    if (row >> step >> time >> atoms >> ke >> sweeps >> overlap && (row >> std::ws).eof()) {
      ++rows;
      EXPECT_LT(overlap, 0.04) << line;
    }
  }
  EXPECT_GE(rows, 11);  // one a time unit
  expect_in_the_box(run.folder / "pour.final", 0.01);
  std::filesystem::remove_all(run.folder);
}

// Nearly elastic grains rebound: a light grain bouncing back at e v and struck by a heavier one
// still falling leaves at up to (1 + e + e^2) v, three times the fall speed v at e 0.99. The deck's
// step follows that rule (dt 0.0032); by the fall speed alone (dt 0.009) a grain at 11.6 moved
// more than half the skin at t = 5.4 and the fix stopped the run.
TEST(PourExample, NearlyElasticPourStaysWithinTheSkin)
{
  const auto run = run_example("in.pour_rigid", "-var e 0.99");
  expect_clean(run);
  EXPECT_EQ(run.output.find("more than half the neighbour skin"), std::string::npos);
  EXPECT_EQ(pour_value(run.output, "grains"), 1000);
  EXPECT_EQ(pour_value(run.output, "capped"), 0);
  expect_in_the_box(run.folder / "pour.final", 0.01);
  std::filesystem::remove_all(run.folder);
}

// LAMMPS's funnel in 2D, its walls LAMMPS regions (a cone over an outlet tube): the first batch
// of 77 and the rest poured in, held while the outlet is closed, every grain through once it is
// open, every solve converged and the overlaps within a hundredth of a diameter (impacts at up to
// 10 sqrt(g d): (1 - theta) dt dv = 0.025 at dt 0.005, far less once the grains share it).
TEST(FunnelExample, FillsThenDrainsThroughItsRegionWalls)
{
  const auto run = run_example("in.funnel_rigid", "-var grains 100 -var fill 10 -var drain 25");
  expect_clean(run);
  EXPECT_EQ(printed_value(run.output, "FUNNEL filled", "grains"), 100);
  EXPECT_EQ(printed_value(run.output, "FUNNEL filled", "above"), 100);
  EXPECT_LT(printed_value(run.output, "FUNNEL filled", "overlap"), 0.01);
  EXPECT_EQ(printed_value(run.output, "FUNNEL drained", "above"), 0);
  EXPECT_EQ(printed_value(run.output, "FUNNEL drained", "capped"), 0);
  EXPECT_LT(printed_value(run.output, "FUNNEL drained", "overlap"), 0.01);
  std::filesystem::remove_all(run.folder);
}

// The drum and its soft twin, shortened: the grains settle in the drum at rest, then it turns a
// fiftieth of a turn at Fr 1e-2; every solve converged, the rigid contacts' overlaps within a
// thousandth of a diameter.
TEST(DrumExample, RigidDrumTurns)
{
  const auto run = run_example("in.drum_rigid", "-var froude 1e-2 -var turns 0.02 -var settle 5");
  expect_clean(run);
  EXPECT_EQ(printed_value(run.output, "DRUM", "grains"), 806);
  EXPECT_EQ(printed_value(run.output, "DRUM", "unconverged"), 0);
  EXPECT_LT(printed_value(run.output, "DRUM", "overlap"), 1e-3);
  EXPECT_TRUE(std::filesystem::exists(run.folder / "dump.drum"));
  std::filesystem::remove_all(run.folder);
}

TEST(DrumExample, SoftTwinTurns)
{
  const auto run = run_example("in.drum_granular", "-var froude 1e-2 -var turns 0.002 -var settle 0.5");
  expect_clean(run);
  EXPECT_EQ(printed_value(run.output, "DRUM", "grains"), 806);
  std::filesystem::remove_all(run.folder);
}

// The 2D silo (inputs/examples/in.silo_rigid) on a small box: 300 grains in a silo 20 wide with
// an orifice of 6, settled, then flowing for 6 time units through the periodic box. The packing
// at rest, the discharged mass growing and counted by the image flags, every solve converged and
// the overlaps within a hundredth of a diameter; the soft twin (in.silo_granular) opens on the
// packing the rigid deck wrote and flows too.
TEST(SiloExample, SettlesThenDischargesThroughTheOrifice)
{
  const auto run = run_example("in.silo_rigid", "-var grains 300 -var width 20 -var D 6 -var fill 10 -var flow 6");
  expect_clean(run);
  EXPECT_EQ(printed_value(run.output, "SILO filled", "grains"), 300);
  const double phi = printed_value(run.output, "SILO filled", "phi");
  EXPECT_GT(phi, 0.7);
  EXPECT_LT(phi, 0.86);
  EXPECT_LT(printed_value(run.output, "SILO filled", "overlap"), 0.01);
  EXPECT_EQ(printed_value(run.output, "SILO done", "grains"), 300);
  EXPECT_EQ(printed_value(run.output, "SILO done", "capped"), 0);
  EXPECT_LT(printed_value(run.output, "SILO done", "overlap"), 0.01);
  // silo.flow: a line every 0.25 time units (each clog check's run repeats its first one), the
  // discharged mass never falling and, after the first grains have fallen below the floor,
  // growing (at D = 6 about 6 per time unit).
  std::ifstream flow(run.folder / "silo.flow");
  std::string line;
  double time, mass, clogs, last = 0;
  int rows = 0;
  while (std::getline(flow, line)) {
    std::istringstream row(line);
    if (line[0] == '#' || !(row >> time >> mass >> clogs)) continue;
    ++rows;
    EXPECT_GE(mass, last - 1e-9) << line;
    last = mass;
  }
  EXPECT_GE(rows, 25);
  EXPECT_NEAR(time, 6.0, 1e-9);
  EXPECT_GT(last, 5.0);
  EXPECT_NEAR(printed_value(run.output, "SILO done", "discharged"), last, 1e-5);
  const auto filled = run.folder / "silo.filled.data";
  ASSERT_TRUE(std::filesystem::exists(filled));
  const auto soft =
      run_example("in.silo_granular", "-var D 6 -var width 20 -var fill 0.2 -var flow 1 -var start " + filled.string());
  expect_clean(soft);
  EXPECT_EQ(printed_value(soft.output, "SILO filled", "grains"), 300);
  EXPECT_EQ(printed_value(soft.output, "SILO done", "grains"), 300);
  EXPECT_GE(printed_value(soft.output, "SILO done", "discharged"), 0);
  std::filesystem::remove_all(run.folder);
  std::filesystem::remove_all(soft.folder);
}

TEST(PourExample, SoftTwinRuns)
{
  // One time unit (10 000 steps): the first batch poured and falling, Hertz contacts set up.
  const auto run = run_example("in.pour_granular", "-var duration 1");
  expect_clean(run);
  EXPECT_EQ(pour_value(run.output, "grains"), 224);
  EXPECT_GT(pour_value(run.output, "ke"), 0);
  expect_in_the_box(run.folder / "pour.final", 0.01);
  std::filesystem::remove_all(run.folder);
}

// The value after `key` on the output's last line starting with `tag`.
double tagged_value(const std::string& output, const std::string& tag, const std::string& key)
{
  const auto line = output.rfind("\n" + tag + " ");
  if (line == std::string::npos) return std::nan("");
  std::istringstream words(output.substr(line + 1, output.find('\n', line + 1) - line - 1));
  std::string word;
  double value = std::nan("");
  while (words >> word)
    if (word == key && words >> value) return value;
  return std::nan("");
}

// Least-squares slope of <vx> against the reduced height of fix ave/chunk's profile file.
double profile_slope(const std::filesystem::path& profile)
{
  std::ifstream in(profile);
  std::string line;
  double n = 0, sy = 0, sv = 0, syy = 0, syv = 0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    double chunk, height, count, vx;
    if (line[0] == '#' || !(row >> chunk >> height >> count >> vx)) continue;
    n += 1, sy += height, sv += vx, syy += height * height, syv += height * vx;
  }
  return (n * syv - sy * sv) / (n * syy - sy * sy);
}

// 256 grains at phi 0.72 sheared by 4 at 0.1 / time unit, averaged over strains 2 to 4.
TEST(PlaneShearExample, StressIsSymmetricByTorqueBalanceAndTheRateIsRecovered)
{
  const auto run = run_example("in.plane_shear", "-var side 16 -var phi 0.72 -var strain 4 -var press_steps 2000");
  expect_clean(run);
  auto value = [&](const char* key) { return tagged_value(run.output, "SHEAR", key); };
  const double rate = value("rate"), area = value("lx") * value("ly");
  EXPECT_NEAR(value("phi"), 0.72, 1e-6);
  // Compressive normal stresses, and a shear stress resisting the shear (vx grows with y).
  EXPECT_GT(value("contact_xx"), 0.0);
  EXPECT_GT(value("contact_yy"), 0.0);
  EXPECT_LT(value("contact_xy"), 0.0);
  EXPECT_GT(value("pyy"), value("contact_yy"));  // the kinetic part adds
  EXPECT_LT(value("pxy"), 0.0);
  // Torque balance: sum over contacts of l x p = sum (r_a + r_b + gap) p_t, and every contact
  // turns its two grains by -r p_t / I: the antisymmetric part xy - yx is minus the rate of the
  // grains' spin angular momentum per area, over the averaging window. Left: the gap's share of
  // the lever (a few 1e-4 d), far below 1 % of the shear stress.
  const double spin_rate = (value("spin_end") - value("spin_start")) / (area * value("time"));
  EXPECT_NEAR(value("contact_xy") - value("contact_yx"), -spin_rate, 0.01 * std::fabs(value("contact_xy")));
  // The imposed rate from the mean velocity profile (reduced height: divide by ly), within the
  // scatter of 2 strains of 256 grains (a few %).
  EXPECT_NEAR(profile_slope(run.folder / "profile.shear") / value("ly"), rate, 0.05 * rate);
  EXPECT_EQ(value("capped"), 0);
  std::filesystem::remove_all(run.folder);
}

}  // namespace
