// The cdpost executable end to end on synthetic run directories.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "lammps_text.h"
#include "synthetic_run.h"

namespace cdpost {
namespace {

struct Outcome {
  int status;
  std::string out, err;
};

std::string slurp(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Outcome cdpost(const std::string& arguments)
{
  auto dir = testing::scratch_dir();
  std::string command = std::string(CDPOST_EXE) + " " + arguments + " >" + (dir / "out.txt").string() + " 2>" +
                        (dir / "err.txt").string();
  int status = std::system(command.c_str());
  return {WEXITSTATUS(status), slurp(dir / "out.txt"), slurp(dir / "err.txt")};
}

std::map<std::string, double> csv_values(const std::filesystem::path& csv);

size_t line_count(const std::string& text)
{
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

// A synthetic run of `duration` s with flow.time alone (no chunk files, no dump) in the
// scratch folder `name`; returns its folder.
std::filesystem::path flow_only_run(const std::string& name, double duration, testing::SyntheticRun& truth)
{
  auto dir = testing::scratch_dir() / name;
  truth.duration = duration;
  truth.with_chunks_and_dump = false;
  testing::write_synthetic_run(dir, truth);
  return dir;
}

// The value column of row `name` in a name,value,error,... CSV.
double csv_value(const std::filesystem::path& csv, const std::string& name)
{
  std::istringstream lines(slurp(csv));
  std::string line;
  while (std::getline(lines, line))
    if (line.rfind(name + ",", 0) == 0) return std::stod(line.substr(name.size() + 1));
  ADD_FAILURE() << "no row " << name << " in " << csv;
  return 0;
}

TEST(Cli, HelpAndUsageErrors)
{
  auto help = cdpost("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("series MANIFEST"), std::string::npos);
  auto run_help = cdpost("run --help");
  EXPECT_EQ(run_help.status, 0);
  EXPECT_NE(run_help.out.find("--col-v-flow NAME"), std::string::npos);
  auto unknown = cdpost("run . --frobnicate 3");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_EQ(unknown.err, "cdpost: cdpost run: unknown option '--frobnicate' (see cdpost --help)\n");
  EXPECT_EQ(cdpost("run . --dt abc").status, 2);
  EXPECT_EQ(cdpost("transmogrify").status, 2);
  auto zero_rate = cdpost("run . --sample-rate 0");
  EXPECT_EQ(zero_rate.status, 2);
  EXPECT_EQ(zero_rate.err, "cdpost: cdpost run: --sample-rate must be positive (see cdpost --help)\n");
}

// Every command that measures the creep refuses a bad --creep-floor or --creep-depth in one line.
TEST(Cli, CreepOptionsRefuseBadValues)
{
  for (const std::string command : {"run .", "series manifest.csv", "creep profile.csv"}) {
    const std::string name = "cdpost " + command.substr(0, command.find(' '));
    for (const std::string option : {"creep-floor", "creep-depth"}) {
      auto text = cdpost(command + " --" + option + " abc");
      EXPECT_EQ(text.status, 2);
      EXPECT_EQ(text.err, "cdpost: " + name + ": --" + option + ": 'abc' is not a number (see cdpost --help)\n");
      for (const std::string bad : {"0", "-1e-4"}) {
        auto refused = cdpost(command + " --" + option + " " + bad);
        EXPECT_EQ(refused.status, 2);
        EXPECT_EQ(refused.err, "cdpost: " + name + ": --" + option + " must be positive (see cdpost --help)\n");
      }
    }
  }
}

// A published run folder (profile.csv, results.csv, results.json): u = 1.4 exp(z / 1.5 d) below
// the wall tops over a floor of +-4e-5 sqrt(g d) that changes sign from bin to bin.
std::filesystem::path published_run(const std::string& name)
{
  auto dir = testing::scratch_dir() / name;
  std::filesystem::create_directories(dir);
  std::ofstream profile(dir / "profile.csv");
  profile << "z_d,u_sqrt_gd,count\n";
  for (int bin = 0; bin < 40; ++bin) {
    const double z = -29.5 + bin;
    const double u = z < 0 ? 1.4 * std::exp(z / 1.5) + (bin % 2 ? 4e-5 : -4e-5) * (1 + 0.1 * (bin % 3)) : 2 + z;
    profile << z << ',' << u << ",40\n";
  }
  std::ofstream(dir / "results.csv") << "name,value,error,unit,description\n"
                                        "U,15.9686061,0.03584441552,sqrt(g d),\"mean x-velocity, z > 0\"\n"
                                        "creep_lambda,2.48,0.22,d,old\ncreep_u0,0.35,0.22,sqrt(g d),old\n"
                                        "phi_bulk,0.766,,,bulk\n";
  std::ofstream(dir / "results.json")
      << "{\n  \"results\": [],\n  \"warnings\": [\"flow.time: a \\\"quoted\\\" word\", "
         "\"profile.chunk: creep fit skipped: old\"]\n}\n";
  return dir;
}

TEST(Cli, CreepRereadsAPublishedProfile)
{
  auto dir = published_run("published");
  auto printed = cdpost("creep " + (dir / "profile.csv").string());
  ASSERT_EQ(printed.status, 0) << printed.err;
  EXPECT_NE(printed.out.find("creep_lambda_band_0_3"), std::string::npos) << printed.out;
  EXPECT_EQ(slurp(dir / "results.csv").find("creep_floor"), std::string::npos);  // nothing written

  auto refused = cdpost("creep " + (dir / "profile.csv").string() + " --update");
  EXPECT_EQ(refused.status, 2);
  EXPECT_EQ(refused.err, "cdpost: cdpost creep: --update needs a published run folder (holding results.csv), not " +
                             (dir / "profile.csv").string() + " (see cdpost --help)\n");

  auto updated = cdpost("creep " + dir.string() + " --update");
  ASSERT_EQ(updated.status, 0) << updated.err;
  const auto values = csv_values(dir / "results.csv");
  EXPECT_NEAR(values.at("creep_lambda"), 1.5, 0.05);
  EXPECT_NEAR(values.at("creep_floor"), 4.4e-5, 0.5e-5);  // rms of the +-(4, 4.4, 4.8)e-5 floor
  EXPECT_EQ(values.at("creep_z_high"), -0.5);
  // The other rows as they were, the creep rows where the old ones stood.
  const auto csv = slurp(dir / "results.csv");
  EXPECT_EQ(csv.rfind("name,value,error,unit,description\nU,15.9686061,0.03584441552,sqrt(g d),\"mean x-velocity, z > "
                      "0\"\ncreep_floor,",
                      0),
            0u)
      << csv;
  EXPECT_NE(csv.find("\nphi_bulk,0.766,,,bulk\n"), std::string::npos) << csv;
  const auto json = slurp(dir / "results.json");
  EXPECT_NE(json.find("\"name\": \"creep_lambda_band_0_3\""), std::string::npos);
  EXPECT_NE(json.find("\"warnings\": [\"flow.time: a \\\"quoted\\\" word\"]"), std::string::npos) << json;

  // Given a floor 10 x higher, the range is shorter; too high a floor leaves it unresolved, said.
  auto given = cdpost("creep " + dir.string() + " --creep-floor 0.05");
  ASSERT_EQ(given.status, 0) << given.err;
  EXPECT_EQ(given.out.find("creep_lambda "), std::string::npos) << given.out;
  EXPECT_EQ(given.err, "cdpost: warning: " + (dir / "profile.csv").string() +
                           ": creep unresolved: 2 bins below the wall tops before u first falls below 10 x the floor "
                           "(0.05 sqrt(g d), given (--creep-floor)); 4 needed\n");
}

// A sample rate whose grid the file's rows cannot lie on fails in one line naming the file.
TEST(Cli, SampleRateTheFileDoesNotFitIsRefused)
{
  testing::SyntheticRun truth;
  auto dir = flow_only_run("rate", 2.0, truth);
  auto finer = cdpost("spectrum " + (dir / "flow.time").string() + " --column v_v_flow --sample-rate 4000");
  EXPECT_EQ(finer.status, 1);
  EXPECT_EQ(finer.err, "cdpost: error: " + (dir / "flow.time").string() +
                           ": sampling interval 0.001000 s is longer than that of the sample rate, 0.000250 s\n");
  auto undivided = cdpost("spectrum " + (dir / "flow.time").string() + " --column v_v_flow --sample-rate 300");
  EXPECT_EQ(undivided.status, 1);
  EXPECT_NE(undivided.err.find("does not divide 0.003333 s"), std::string::npos) << undivided.err;
  EXPECT_EQ(line_count(undivided.err), 1u) << undivided.err;
}

TEST(Cli, RunWritesResultsFiguresAndReport)
{
  auto dir = testing::scratch_dir() / "run";
  testing::SyntheticRun truth;
  truth.duration = 4.0;
  testing::write_synthetic_run(dir, truth);
  auto outcome = cdpost(dir.string() + " --dump " + (dir / "dump.chute.gz").string());
  EXPECT_EQ(outcome.status, 2);  // the subcommand is missing
  outcome = cdpost("run " + dir.string() + " --dump " + (dir / "dump.chute.gz").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.out.find("f "), std::string::npos);
  EXPECT_NEAR(csv_value(dir / "post/results.csv", "f"), truth.frequency, 1.0);
  EXPECT_NE(slurp(dir / "post/results.json").find("\"name\": \"A_mean\""), std::string::npos);
  for (const char* figure : {"u_t", "spectrum", "profile", "spectra_depth", "snapshot"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "post/figures" / (std::string(figure) + ".png"))) << figure;
    EXPECT_TRUE(std::filesystem::exists(dir / "post/figures" / (std::string(figure) + ".svg"))) << figure;
    EXPECT_NE(slurp(dir / "post/report.md").find("figures/" + std::string(figure) + ".png"), std::string::npos);
  }
}

// A run whose wall tops stand 10 d above the floor: its chute.params gives z0, the sample rate,
// d and g. u(z) is Bagnold above z = 0 on a slip of 0.3 sqrt(g d) and u0 exp(z/3 d) below, with
// u0 = the slip; measured from the floor (z0 = 0) every bin sits 10 d too high and the creep
// fit reads u0 = 0.3 exp(-10/3) instead.
constexpr double kWallTopsD = 10;

std::filesystem::path run_with_wall_tops(const std::string& name, testing::SyntheticRun& truth)
{
  auto dir = testing::scratch_dir() / name;
  truth.duration = 4.0;
  truth.y_top = kWallTopsD * truth.d;
  testing::write_synthetic_run(dir, truth);
  return dir;
}

// The columns of columns.chunk tile the cell whose length chute.params records: no option needed.
TEST(Cli, RunTakesTheCellLengthFromTheRunFolder)
{
  testing::SyntheticRun truth;
  truth.with_columns = true;
  truth.recorded_length_d = 45;
  auto dir = run_with_wall_tops("columns", truth);
  auto outcome = cdpost("run " + dir.string() + " --t-start 2.5");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.out.find(", L 45 d from " + (dir / "chute.params").string()), std::string::npos) << outcome.out;
  EXPECT_EQ(outcome.err.find("cell-length"), std::string::npos) << outcome.err;
  EXPECT_DOUBLE_EQ(csv_value(dir / "post/results.csv", "column_width"), 1.5);  // 30 columns tiling 45 d
}

TEST(Cli, RunTakesTheWallTopsAndSampleRateFromTheRunFolder)
{
  testing::SyntheticRun truth;
  auto dir = run_with_wall_tops("run", truth);
  auto outcome = cdpost("run " + dir.string() + " --dump " + (dir / "dump.chute.gz").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const std::string said =
      "parameters: z0 0.005 m, sample rate 1000 Hz, d 0.0005 m, g 9.81 m/s^2 from " + (dir / "chute.params").string();
  EXPECT_EQ(outcome.out.substr(0, outcome.out.find('\n')), said);
  EXPECT_NE(slurp(dir / "post/report.md").find("Parameters: z0 0.005 m, sample rate 1000 Hz"), std::string::npos);
  const auto values = csv_values(dir / "post/results.csv");
  // Profile bins carry 2 % noise: the fitted u0 within 5 % of the slip.
  EXPECT_NEAR(values.at("creep_u0"), 0.3, 0.05 * 0.3);
  EXPECT_NEAR(values.at("creep_lambda"), truth.creep_lambda, 0.1 * truth.creep_lambda);
  EXPECT_GT(values.at("bagnold_r2"), 0.99);

  // The command line wins over the record, and says so.
  outcome = cdpost("run " + dir.string() + " --z0 0 --sample-rate 500 --out " + (dir / "floor").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_EQ(outcome.out.substr(0, outcome.out.find('\n')),
            "parameters: z0 0 m from --z0; sample rate 500 Hz from --sample-rate; d 0.0005 m, g 9.81 m/s^2 from " +
                (dir / "chute.params").string());
  EXPECT_NEAR(csv_value(dir / "floor/results.csv", "creep_u0"), 0.3 * std::exp(-kWallTopsD / truth.creep_lambda),
              0.05 * 0.3 * std::exp(-kWallTopsD / truth.creep_lambda));

  // A dump's snapshot takes the wall tops from the record beside it.
  outcome = cdpost("snapshot " + (dir / "dump.chute.gz").string() + " --out " + (dir / "snap").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_EQ(outcome.out.rfind("parameters: z0 0.005 m,", 0), 0u) << outcome.out;
}

TEST(Cli, RunFolderRecordingNothingNeedsZ0)
{
  testing::SyntheticRun truth;
  truth.with_record = false;
  auto dir = run_with_wall_tops("run", truth);
  auto refused = cdpost("run " + dir.string());
  EXPECT_EQ(refused.status, 1);
  EXPECT_EQ(refused.err, "cdpost: error: " + dir.string() +
                             ": no chute.params (inputs/in.chute writes it): give --z0, the height of the wall tops "
                             "that z is measured from\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "post"));

  auto given = cdpost("run " + dir.string() + " --z0 0.005");
  ASSERT_EQ(given.status, 0) << given.err;
  EXPECT_EQ(given.out.substr(0, given.out.find('\n')),
            "parameters: z0 0.005 m from --z0; sample rate none given or recorded (the time file's longest "
            "interval); d 0.0005 m, g 9.81 m/s^2 by default");
  EXPECT_NEAR(csv_value(dir / "post/results.csv", "creep_u0"), 0.3, 0.05 * 0.3);

  // A series reads each run's record: the same folder in a manifest fails on its line.
  std::ofstream(dir.parent_path() / "series.csv") << "run,mu,theta\nrun,0.5,24\n";
  auto series = cdpost("series " + (dir.parent_path() / "series.csv").string());
  EXPECT_EQ(series.status, 1);
  EXPECT_NE(series.err.find("series.csv:2: run failed: " + dir.string() + ": no chute.params"), std::string::npos)
      << series.err;
  EXPECT_NE(series.err.find("give --z0"), std::string::npos) << series.err;
  EXPECT_EQ(line_count(series.err), 1u) << series.err;

  testing::write_file(dir / "chute.params", "y_top_m 0.005\nsample_rate_hz fast\n");
  auto malformed = cdpost("run " + dir.string());
  EXPECT_EQ(malformed.err,
            "cdpost: error: " + (dir / "chute.params").string() + ":2: bad number 'fast' for sample_rate_hz\n");
}

// U(t) relaxes as 1 - exp(-t / 0.4 s): a window from t = 0 drifts by most of U, one from 2.5 s
// by 10 exp(-6.25) = 0.02 sqrt(g d) of 10, well within 2 %.
TEST(Cli, ForcedWindowThatDriftsIsLabelledEverywhere)
{
  testing::SyntheticRun truth;
  auto dir = run_with_wall_tops("run", truth);
  auto outcome = cdpost("run " + dir.string() + " --t-start 0");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  // The window's warning first, once (the synthetic run has no columns.chunk: a line says that).
  EXPECT_EQ(outcome.err.rfind("cdpost: warning: the window t = 0.001 to ", 0), 0u) << outcome.err;
  EXPECT_EQ(outcome.err.find("not stationary", outcome.err.find('\n')), std::string::npos) << outcome.err;
  EXPECT_NE(outcome.err.find(" sqrt(d/g)) is not stationary: U drifts by "), std::string::npos) << outcome.err;
  EXPECT_NE(outcome.err.find("above the 2% the stationarity test allows (--max-drift)"), std::string::npos);
  const auto json = slurp(dir / "post/results.json");
  EXPECT_NE(json.find("\"warnings\": [\"the window t = 0.001 to "), std::string::npos) << json;
  const auto report = slurp(dir / "post/report.md");
  EXPECT_NE(report.find("Window given on the command line, not stationary: U drifts by"), std::string::npos);
  EXPECT_NE(report.find("*Spectrum of v(t) over the window (not stationary)*"), std::string::npos);
  EXPECT_NE(report.find("## Warnings\n\n- the window t = 0.001 to "), std::string::npos);
  EXPECT_EQ(report.find("stationary window"), std::string::npos);
  EXPECT_NE(slurp(dir / "post/figures/u_t.gp").find("shaded: window (not stationary)"), std::string::npos);
  // The spectrum's own panel, which a reader may see without the report, says it too.
  EXPECT_NE(slurp(dir / "post/figures/spectrum.gp").find("set title 'NOT STATIONARY (U drifts by "), std::string::npos);
  EXPECT_NE(slurp(dir / "post/results.csv").find("start of the given window (not stationary)"), std::string::npos);

  outcome = cdpost("run " + dir.string() + " --t-start 2.5 --out " + (dir / "late").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_EQ(outcome.err.find("not stationary"), std::string::npos) << outcome.err;
  EXPECT_LT(csv_value(dir / "late/results.csv", "stationary_drift"), 0.02);
  EXPECT_EQ(slurp(dir / "late/figures/spectrum.gp").find("NOT STATIONARY"), std::string::npos);
  EXPECT_NE(slurp(dir / "late/report.md").find("Stationary window given on the command line, U drifts by"),
            std::string::npos);
  EXPECT_NE(slurp(dir / "late/figures/u_t.gp").find("shaded: stationary window"), std::string::npos);

  // With columns.chunk, the along-the-cell paragraph names the forced window as the rest do.
  truth.with_columns = true;
  truth.recorded_length_d = 45;
  dir = run_with_wall_tops("columns", truth);
  outcome = cdpost("run " + dir.string() + " --t-start 0");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const auto along = slurp(dir / "post/report.md");
  EXPECT_NE(along.find("tiling the cell (columns.chunk), over the window (not stationary)."), std::string::npos)
      << along;
  EXPECT_EQ(along.find("stationary window"), std::string::npos);
}

TEST(Cli, BrokenInputGivesOneLineNamingFileAndLine)
{
  testing::SyntheticRun truth;
  auto dir = flow_only_run("run", 1.0, truth);
  auto text = slurp(dir / "flow.time");
  testing::write_file(dir / "flow.time", text.substr(0, text.size() - 30));  // cut inside the last row
  auto outcome = cdpost("run " + dir.string());
  EXPECT_EQ(outcome.status, 1);
  EXPECT_EQ(line_count(outcome.err), 1u) << outcome.err;
  EXPECT_EQ(outcome.err.rfind("cdpost: error: " + (dir / "flow.time").string() + ":1001: expected 7 values", 0), 0u)
      << outcome.err;

  testing::write_file(dir / "flow.time", "");
  outcome = cdpost("run " + dir.string());
  EXPECT_EQ(outcome.err, "cdpost: error: " + (dir / "flow.time").string() + ": file is empty\n");
  EXPECT_EQ(cdpost("snapshot " + (dir / "nothing.gz").string()).status, 1);
}

TEST(Cli, SnapshotOfAnyDumpTakesItsDiameterAndPeriodicityFromIt)
{
  // LAMMPS's pour into a box (f fm p), in LJ units: grains of diameter 0.5 to 1, no chute.params.
  const auto dir = testing::scratch_dir();
  const auto dump = testing::write_file(
      dir / "dump.pour",
      testing::dump_frame_text(25000, 100, 50, {{1, 10, 0.4, 0, 0, 0.25}, {2, 90, 0.5, 0, 0, 0.5}}, "ff fm pp"));
  auto outcome = cdpost("snapshot " + dump + " --units reduced");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_EQ(outcome.out.substr(0, outcome.out.find('\n')),
            "snapshot: d 0.75 input length units (the dump's mean diameter); not periodic (the dump's box bounds); "
            "input in reduced units (g = 1 in the dump's units)");
  const auto script = slurp(dir / "snapshot.gp");
  EXPECT_EQ(script.find("periodic images"), std::string::npos);
  EXPECT_NE(script.find("xrange [0:133.333"), std::string::npos) << script;  // 100 / 0.75: x in d
  outcome = cdpost("snapshot " + dump + " --units reduced --d 1 --periodic x");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.out.find("d 1 m (from --d or chute.params); periodic in x (from --periodic); input in reduced "
                             "units (lengths in d, times in sqrt(d/g))"),
            std::string::npos)
      << outcome.out;
  EXPECT_EQ(cdpost("snapshot " + dump + " --periodic z").err,
            "cdpost: cdpost snapshot: --periodic takes x, y, xy or none, not 'z' (see cdpost --help)\n");
}

// The user trial: a report said nothing of the solver's health. Every report and results.json
// gives it, or says it was not recorded.
TEST(Cli, ReportsGiveTheSolversHealthOrSayItIsNotRecorded)
{
  testing::SyntheticRun truth;
  truth.with_solver = false;
  auto dir = run_with_wall_tops("health", truth);
  auto outcome = cdpost("run " + dir.string() + " --t-start 2.5");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.err.find("cdpost: warning: " + (dir / "solver.time").string() +
                             " not found: the solver's health is not recorded"),
            std::string::npos)
      << outcome.err;
  auto report = slurp(dir / "post/report.md");
  EXPECT_NE(report.find("## Solver health\n\nUnconverged steps, sweeps per step and the largest interpenetration: "
                        "not recorded (no " +
                        (dir / "solver.time").string() + ")."),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("| `solver_sweeps_p99` | not recorded |"), std::string::npos);
  const auto json = slurp(dir / "post/results.json");
  for (const char* name : {"solver_unconverged_steps", "solver_unconverged_fraction", "solver_sweeps_median",
                           "solver_sweeps_p99", "solver_overlap_max", "solver_overlap_largest"})
    EXPECT_NE(json.find("{\"name\": \"" + std::string(name) + "\", \"value\": null"), std::string::npos) << name;

  // 3000 of the first 10 000 steps unconverged (of 39 intervals, 390 000 steps), and the log's solver line.
  truth.with_solver = true;
  truth.unconverged_steps = 3000;
  dir = run_with_wall_tops("health", truth);
  testing::write_file(dir / "log.lammps",
                      "Fix contact/dynamics cd solver: 5539 steps, 111 unconverged (2 %), largest final norm 0.01, "
                      "sweeps per step median 71, 99th percentile 358, max 692, 0 rescued from a stall\n");
  outcome = cdpost("run " + dir.string() + " --t-start 2.5");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.err.find("solver.time: 3000 steps unconverged, 0.76923 % of the steps (more than 0.1 %)"),
            std::string::npos)
      << outcome.err;
  report = slurp(dir / "post/report.md");
  EXPECT_NE(report.find("3000 of 390000 steps unconverged (0.76923 %); sweeps per step, median 40, 99th percentile 40"),
            std::string::npos)
      << report.substr(report.find("## Solver health"), 600);
  EXPECT_NE(report.find("\n1. 5539 steps, 111 unconverged (2 %)"), std::string::npos) << report;
  EXPECT_NE(report.find("not recorded (no SOLVER line in the log)"), std::string::npos) << report;
  EXPECT_NEAR(csv_value(dir / "post/results.csv", "solver_unconverged_fraction"), 3000.0 / 390000, 1e-12);
  EXPECT_DOUBLE_EQ(csv_value(dir / "post/results.csv", "solver_overlap_max"), 1e-3);

  // A broken solver.time is one line naming it.
  testing::write_file(dir / "solver.time", "# Time-averaged data\n# TimeStep f_cd[1] f_cd[5] f_cd[7]\n100 3 0.1 2\n");
  outcome = cdpost("run " + dir.string() + " --t-start 2.5");
  EXPECT_EQ(outcome.status, 1);
  EXPECT_EQ(outcome.err, "cdpost: error: " + (dir / "solver.time").string() +
                             ":3: fraction of converged steps 2 is not in [0, 1]\n");
}

// The parameters line names the input's units: reduced lengths are in d, not metres.
TEST(Cli, UnitsLineIsRightForEveryUnitSystem)
{
  testing::SyntheticRun truth;
  auto dir = run_with_wall_tops("units", truth);
  auto first_line = [](const Outcome& outcome) { return outcome.out.substr(0, outcome.out.find('\n')); };
  const std::string record = (dir / "chute.params").string();
  auto reduced = cdpost("run " + dir.string() + " --units reduced");  // SI files read as reduced: may then fail
  EXPECT_EQ(first_line(reduced),
            "parameters: input in reduced units (lengths in d, times in sqrt(d/g)) from --units; z0 10 d, sample rate "
            "1000 Hz, d 0.0005 m, g 9.81 m/s^2 (converting sqrt(d/g) to s, for the results in Hz and s) from " +
                record)
      << reduced.out;
  auto custom = cdpost("run " + dir.string() + " --length-unit 1e-3 --out " + (dir / "mm").string());
  EXPECT_EQ(first_line(custom),
            "parameters: input length unit 0.001 m, time unit 1 s from --length-unit, "
            "--time-unit; z0 0.005 m, sample rate 1000 Hz, d 0.0005 m, g 9.81 m/s^2 from " +
                record)
      << custom.out;
  auto si = cdpost("run " + dir.string() + " --t-start 2.5");
  ASSERT_EQ(si.status, 0) << si.err;
  EXPECT_NE(slurp(dir / "post/report.md").find("Units: input in SI units (m, s); d = 0.0005 m, g = 9.81 m/s^2"),
            std::string::npos);
  EXPECT_EQ(cdpost("run " + dir.string() + " --time-unit 0").err,
            "cdpost: cdpost run: --time-unit must be positive (see cdpost --help)\n");
  // The snapshot's help says what the command does: without a chute.params it needs --g.
  const auto help = cdpost("snapshot --help").out;
  const auto g_line = help.substr(help.find("  --g "), help.find('\n', help.find("  --g ")) - help.find("  --g "));
  EXPECT_EQ(g_line.find("9.81"), std::string::npos) << g_line;
  EXPECT_NE(g_line.find("without one, needed unless --units reduced"), std::string::npos) << g_line;
}

// Atoms that are not grains (a ring of disks moved by fix move) are drawn as obstacles, in grey.
TEST(Cli, SnapshotDrawsObstaclesApartFromGrains)
{
  const auto dir = testing::scratch_dir();
  std::vector<testing::DumpAtom> atoms = {{1, 10, 10, 1, 0, 0.5}, {2, 20, 10, 2, 0, 0.5}};
  for (long i = 0; i < 8; ++i)
    atoms.push_back({3 + i, 30 + 3 * std::cos(i * M_PI / 4), 20 + 3 * std::sin(i * M_PI / 4), 0, 0, 0.25, 2});
  const auto dump = testing::write_file(dir / "dump.ring", testing::dump_frame_text(100, 40, 30, atoms, "pp ff pp"));
  auto outcome = cdpost("snapshot " + dump + " --g 1 --obstacle-types 2");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.out.find("8 obstacle atoms (from --obstacle-types)"), std::string::npos) << outcome.out;
  const auto script = slurp(dir / "snapshot.gp");
  EXPECT_NE(script.find("lc rgb 'grey50'"), std::string::npos) << script;
  EXPECT_NE(script.find("(2 grains, 8 obstacle atoms)"), std::string::npos) << script;
  EXPECT_NE(script.find("obstacles (atom type 2) in grey"), std::string::npos);
  // Refused in one line: a list that is not one of types, a type no atom has.
  EXPECT_EQ(cdpost("snapshot " + dump + " --g 1 --obstacle-types 2,,3").err,
            "cdpost: cdpost snapshot: --obstacle-types takes positive atom types separated by commas (e.g. 2,3), "
            "not '2,,3' (see cdpost --help)\n");
  EXPECT_EQ(cdpost("snapshot " + dump + " --g 1 --obstacle-types 0").status, 2);
  outcome = cdpost("snapshot " + dump + " --g 1 --obstacle-types 5");
  EXPECT_EQ(outcome.status, 1);
  EXPECT_EQ(outcome.err, "cdpost: error: " + dump +
                             ":1: no atom of the obstacle type(s) 5 in the frame at timestep 100: check "
                             "--obstacle-types\n");
  EXPECT_EQ(cdpost("run " + dir.string() + " --obstacle-types 2").err,
            "cdpost: cdpost run: --obstacle-types is for the snapshot: give --dump too (see cdpost --help)\n");
}

// cdpost fields end to end: the units said in every output, a truncated contact dump named by
// file and line in one line, and the command line's refusals.
TEST(Cli, FieldsOfADumpAndItsContacts)
{
  const auto dir = testing::scratch_dir();
  std::vector<testing::DumpAtom> atoms;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 4; ++j) atoms.push_back({long(1 + i + 10 * j), i + 0.5, j + 0.5, 0.1, 0, 0.5});
  const auto dump = testing::write_file(dir / "dump.stack", testing::dump_frame_text(0, 10, 4, atoms, "pp ff pp") +
                                                                testing::dump_frame_text(1, 10, 4, atoms, "pp ff pp"));
  std::string local;
  for (int step = 0; step < 2; ++step) {
    local += "ITEM: TIMESTEP\n" + std::to_string(step) +
             "\nITEM: NUMBER OF ENTRIES\n10\nITEM: BOX BOUNDS pp ff pp\n0 10\n0 4\n-0.5 0.5\n"
             "ITEM: ENTRIES index f_cd[1] f_cd[2] f_cd[3] f_cd[4] f_cd[5] f_cd[6] f_cd[7]\n";
    for (int i = 0; i < 10; ++i)
      local += std::to_string(i + 1) + " " + std::to_string(i + 1) + " 0 1 0.04 0 " + std::to_string(i + 0.5) + " 0\n";
  }
  const auto contacts = testing::write_file(dir / "contacts.stack", local);
  const std::string common =
      "fields " + dump + " --units lj --density 1 --dt 0.01 --along y --width 0.1 --out " + (dir / "out").string();
  auto outcome = cdpost(common + " --contacts " + contacts);
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.out.find("fields: units LJ: lengths sigma, times tau"), std::string::npos) << outcome.out;
  EXPECT_NE(outcome.out.find("2 frames, timesteps 0 to 1; 10 contacts a frame"), std::string::npos) << outcome.out;
  const auto table = slurp(dir / "out" / "fields.csv");
  EXPECT_NE(table.find("y_sigma,phi,rho_m/sigma^3,ux_sigma/tau"), std::string::npos) << table.substr(0, 400);
  EXPECT_NE(slurp(dir / "out" / "fields.json").find("\"stress_unit\": \"m/(sigma tau^2)\""), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "fields_profile.png"));

  testing::write_file(dir / "contacts.stack", local.substr(0, local.size() - 30));  // cut inside the last row
  outcome = cdpost(common + " --contacts " + contacts);
  EXPECT_EQ(outcome.status, 1);
  EXPECT_EQ(line_count(outcome.err), 1u) << outcome.err;
  EXPECT_EQ(outcome.err.rfind("cdpost: error: " + contacts + ":", 0), 0u) << outcome.err;

  EXPECT_EQ(cdpost("fields " + dump + " --width 0.1").err,
            "cdpost: cdpost fields: no chute.params beside " + dump +
                " to take the units from: give --units si or --units lj (see cdpost --help)\n");
  EXPECT_EQ(cdpost(common + " --kernel box").status, 2);
  EXPECT_EQ(cdpost(common + " --cells 3,4").status, 2);  // a profile takes N
  EXPECT_EQ(cdpost(common + " --polar 5,2,1").status, 2);
  EXPECT_EQ(cdpost(common + " --contacts " + contacts + " --dt 0").status, 2);
}

// Bins above the measured h (the dilute surface) are drawn apart from the fitted layer and named.
TEST(Cli, ProfileNamesTheBinsAboveTheLayer)
{
  testing::SyntheticRun truth;
  truth.occupied_above_h = 3;
  auto dir = run_with_wall_tops("surface", truth);
  ASSERT_EQ(cdpost("run " + dir.string() + " --t-start 2.5").status, 0);
  const auto script = slurp(dir / "post/figures/profile.gp");
  EXPECT_NE(script.find("title 'u(z) above h: dilute surface, few grains, not fitted'"), std::string::npos) << script;
  EXPECT_NE(script.find("pt 6 ps 1 lt 1 title 'u(z) above h"), std::string::npos);  // open circles
}

// A dump that no chute.params describes gives no g: the snapshot, whose colours are u_x / sqrt(g d),
// asks for it (an LJ pour coloured with 9.81 m/s^2 would read 3x off) and takes it when given.
TEST(Cli, SnapshotOfANonChuteDumpAsksForGravity)
{
  const auto dir = testing::scratch_dir();
  const auto dump = testing::write_file(
      dir / "dump.pour",
      testing::dump_frame_text(25000, 100, 50, {{1, 10, 0.4, 0, 0, 0.25}, {2, 90, 0.5, 0, 0, 0.5}}, "ff fm pp"));
  auto outcome = cdpost("snapshot " + dump);
  EXPECT_EQ(outcome.status, 1);
  EXPECT_EQ(outcome.err, "cdpost: error: " + dump +
                             ": no chute.params beside it to take g and the units from: give --g, gravity in the "
                             "dump's units (the colours are u_x / sqrt(g d)), or --units reduced\n");
  outcome = cdpost("snapshot " + dump + " --g 1");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "snapshot.png"));
}

// A window given backwards is named as such, and one that misses the run says where the run is.
TEST(Cli, WindowEndingBeforeItStartsIsNamed)
{
  testing::SyntheticRun truth;
  auto dir = run_with_wall_tops("backwards", truth);
  auto outcome = cdpost("run " + dir.string() + " --t-start 3 --t-end 2");
  EXPECT_EQ(outcome.status, 2);
  EXPECT_EQ(outcome.err,
            "cdpost: cdpost run: --t-end 2 is not after --t-start 3: the window ends before it starts (see cdpost "
            "--help)\n");
  outcome = cdpost("run " + dir.string() + " --t-start 7 --t-end 9");
  EXPECT_EQ(outcome.status, 1);
  EXPECT_NE(outcome.err.find("the window from t = 7 s to 9 s holds fewer than 2 samples (the run's "),
            std::string::npos)
      << outcome.err;
  EXPECT_NE(outcome.err.find(" samples span 0"), std::string::npos) << outcome.err;
}

TEST(Cli, BinaryDumpIsRefusedInOneShortLine)
{
  // 15 KB of a binary dump's bytes: the error names the file and says what it is, nothing more.
  const auto dir = testing::scratch_dir();
  std::string bytes(15000, '\0');
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 131) % 256);
  const auto dump = testing::write_file(dir / "dump.bin", bytes);
  const auto outcome = cdpost("snapshot " + dump);
  EXPECT_EQ(outcome.status, 1);
  EXPECT_EQ(outcome.err, "cdpost: error: " + dump +
                             ":1: binary data, not text: cdpost reads LAMMPS text output, plain or gzip-compressed "
                             "(write dumps with dump custom, not a binary .bin dump)\n");
}

TEST(Cli, SpectrumOfOneColumn)
{
  testing::SyntheticRun truth;
  auto dir = flow_only_run("run", 2.0, truth);
  auto outcome =
      cdpost("spectrum " + (dir / "flow.time").string() + " --column v_v_flow --out " + (dir / "s").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NEAR(csv_value(dir / "s/spectrum_results.csv", "f"), truth.frequency, 1.0);
}

// A series following the mu(I) rule (I0 = 0.3) with f = 0.9 (sqrt(g d)/U g/d)^(1/2),
// phi = phi_c(mu) - 0.002 U/sqrt(g d), plus an L series.
TEST(Cli, SeriesRecoversTheFlowRulesAndScalings)
{
  auto dir = testing::scratch_dir();
  std::ofstream manifest(dir / "series.csv");
  manifest << "# synthetic series\nrun,mu,theta,L\n";
  struct Friction {
    double mu, theta1, theta2, phi_c;
    std::vector<double> angles;
  };
  const std::vector<Friction> frictions = {{0.05, 15, 26, 0.82, {16, 17.5, 19, 20.5, 22}},
                                           {0.5, 21, 33, 0.80, {22, 23.5, 25, 26.5, 28}}};
  int index = 0;
  for (const auto& friction : frictions)
    for (double theta : friction.angles) {
      auto t = [](double deg) { return std::tan(deg * M_PI / 180); };
      testing::SyntheticRun run;
      run.duration = 2.5;
      run.relaxation = 0.1;
      run.with_chunks_and_dump = false;
      run.seed = static_cast<unsigned>(++index);
      const double inertial = 0.3 * (t(theta) - t(friction.theta1)) / (t(friction.theta2) - t(theta));
      run.u_final = inertial * std::pow(run.h, 1.5);
      run.phi = friction.phi_c - 0.002 * run.u_final;
      run.frequency = 0.9 * std::sqrt(std::sqrt(run.g / run.d) * std::sqrt(run.g / run.d) / run.u_final);
      const std::string name = "run" + std::to_string(index);
      testing::write_synthetic_run(dir / name, run);
      manifest << name << "," << friction.mu << "," << theta << "," << 45 + 10 * index << "\n";
    }
  manifest.close();
  auto outcome = cdpost("series " + (dir / "series.csv").string() + " --out " + (dir / "post").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const auto fits = dir / "post/fits.csv";
  EXPECT_NEAR(csv_value(fits, "muI_I0"), 0.3, 0.03);
  EXPECT_NEAR(csv_value(fits, "muI_theta1_mu0.5"), 21, 0.5);
  EXPECT_NEAR(csv_value(fits, "muI_theta2_mu0.05"), 26, 0.5);
  EXPECT_NEAR(csv_value(fits, "phi_k"), 0.002, 0.0003);
  EXPECT_NEAR(csv_value(fits, "phi_c_mu0.05"), 0.82, 0.003);
  EXPECT_NEAR(csv_value(fits, "f_vs_scale_exponent"), 1.0, 0.1);
  EXPECT_GT(csv_value(fits, "f_vs_scale_correlation"), 0.95);
  EXPECT_NEAR(csv_value(fits, "pouliquen_theta1_mu0.5"), 21, 2.0);
  for (const char* figure :
       {"f_vs_scale", "f_vs_shear_rate", "A_vs_U", "A_vs_phi", "phi_vs_U", "U_vs_theta", "L_series"})
    EXPECT_TRUE(std::filesystem::exists(dir / "post/figures" / (std::string(figure) + ".png"))) << figure;
  EXPECT_EQ(line_count(slurp(dir / "post/runs.csv")), 11u);
  // Runs are named as in the manifest (not by a path of this machine), numbers in full.
  const auto runs = slurp(dir / "post/runs.csv");
  EXPECT_EQ(runs.find(dir.string()), std::string::npos);
  EXPECT_NE(runs.find("\nrun1,0.05,16,55,"), std::string::npos) << runs.substr(0, 400);
  EXPECT_EQ(slurp(dir / "post/residuals.csv").find(dir.string()), std::string::npos);
  // No stopped run: beta free gives l/beta only, and says why.
  EXPECT_GT(csv_value(fits, "pouliquen_betafree_ell_over_beta_mu0.5"), 0);
  EXPECT_EQ(slurp(fits).find("pouliquen_betafree_beta_mu"), std::string::npos);
  EXPECT_NE(slurp(dir / "post/fits.json").find("mu = 0.5: no stopped run, so beta and l are not determined separately"),
            std::string::npos);
  // Residuals: 10 runs in each of pouliquen, pouliquen_betafree, muI, phi_U and phi_I, plus the header;
  // no packing definition, since these runs have no packing.chunk.
  EXPECT_EQ(line_count(slurp(dir / "post/residuals.csv")), 51u);
  EXPECT_NE(slurp(dir / "post/fits.json").find("no run has I_packing"), std::string::npos);
  // phi = phi_c - 0.002 U is phi_c - 0.002 h^1.5 I at the runs' h.
  const double h15 = std::pow(testing::SyntheticRun{}.h, 1.5);
  EXPECT_NEAR(csv_value(fits, "phiI_k"), 0.002 * h15, 0.0003 * h15);
  // I0 and theta2 trade off; held at 0.1 ... 0.5, the rms residual is smallest at the true 0.3.
  EXPECT_GT(csv_value(fits, "muI_corr_I0_theta2_mu0.5"), 0.9);
  std::map<double, double> rms_of_held;
  std::istringstream held(slurp(dir / "post/held_fits.csv"));
  std::string row;
  std::getline(held, row);
  EXPECT_EQ(row.rfind("definition,rule,held_parameter,held_value,mu,", 0), 0u) << row;
  while (std::getline(held, row))
    if (row.rfind("surface,muI,I0,", 0) == 0) {
      std::vector<std::string> fields;
      std::istringstream cells(row);
      for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
      rms_of_held[std::stod(fields[3])] = std::stod(fields[9]);
    }
  ASSERT_EQ(rms_of_held.size(), 6u);
  auto best = std::min_element(rms_of_held.begin(), rms_of_held.end(),
                               [](const auto& a, const auto& b) { return a.second < b.second; });
  EXPECT_EQ(best->first, 0.3);
  EXPECT_GT(csv_value(fits, "muI_rms_residual"), 0);
  // Significance overall and per friction (5 runs each).
  EXPECT_EQ(csv_value(fits, "f_vs_scale_n"), 10);
  EXPECT_LT(csv_value(fits, "f_vs_scale_p_value"), 1e-3);  // r > 0.95 over 10 runs
  EXPECT_EQ(csv_value(fits, "f_vs_scale_n_mu0.05"), 5);
  // f = c (U/h)^(-1/2) exactly at each mu: a curve on linear scales, a line in log-log, whose
  // significance is that of the log-log correlation (r = -1 up to the measurement noise).
  EXPECT_GT(csv_value(fits, "f_vs_shear_rate_correlation_mu0.5"), -0.95);
  EXPECT_LT(csv_value(fits, "f_vs_shear_rate_log_correlation_mu0.5"), -0.999);
  EXPECT_LT(csv_value(fits, "f_vs_shear_rate_p_value_mu0.5"), 1e-4);
  EXPECT_NEAR(csv_value(fits, "f_vs_scale_exponent_mu0.5"), 1.0, 0.1);
  EXPECT_GE(csv_value(fits, "correlation_A_U_p_value_mu0.5"), 0);
  EXPECT_EQ(csv_value(fits, "correlation_f_L_n"), 10);

  std::ofstream(dir / "bad.csv") << "run,mu,theta\nrun1,0.5\n";
  auto bad = cdpost("series " + (dir / "bad.csv").string());
  EXPECT_EQ(bad.err,
            "cdpost: error: " + (dir / "bad.csv").string() + ":2: expected 3 fields (run, mu, theta), found 2\n");
}

// Pouliquen's rule with beta = 0.3, l = 6 (theta1 = 20, theta2 = 33 deg) at mu = 0.5: five
// flowing runs with layers (amplitude decaying as exp((z - h)/20 d)), two at mu = 2, and three stopped runs,
// which have no run directory (a stopped run is not read).
constexpr double kPouliquenBeta = 0.3, kPouliquenEll = 6;

// Writes the runs and DIR/series.csv of that series.
void write_pouliquen_series(const std::filesystem::path& dir)
{
  const double beta = kPouliquenBeta, ell = kPouliquenEll;
  const double tan1 = std::tan(20 * M_PI / 180), tan2 = std::tan(33 * M_PI / 180);
  auto h_stop = [&](double theta) { return -ell * std::log((std::tan(theta * M_PI / 180) - tan1) / (tan2 - tan1)); };
  std::ofstream manifest(dir / "series.csv");
  manifest << "run,mu,theta,L,stopped,h_stop\n";
  int index = 0;
  // Two runs at mu = 2 make a friction too small for a correlation.
  for (auto [mu, theta] :
       {std::pair{0.5, 21.0}, {0.5, 22.5}, {0.5, 24.0}, {0.5, 25.5}, {0.5, 27.0}, {2.0, 28.0}, {2.0, 29.0}}) {
    testing::SyntheticRun run;
    run.duration = 2.5;
    run.relaxation = 0.1;
    run.seed = static_cast<unsigned>(++index);
    run.u_final = beta / h_stop(theta) * std::pow(run.h, 1.5);  // I = beta d/h_stop
    const std::string name = "run" + std::to_string(index);
    testing::write_synthetic_run(dir / name, run);
    manifest << name << "," << mu << "," << theta << ",45,0,\n";
  }
  for (double theta : {20.5, 21.0, 21.5})
    manifest << "stopped" << theta << ",0.5," << theta << ",45,1," << h_stop(theta) << "\n";
}

// name -> value of every row of a results or fits CSV.
std::map<std::string, double> csv_values(const std::filesystem::path& csv)
{
  std::map<std::string, double> values;
  std::istringstream lines(slurp(csv));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    const auto comma = line.find(',');
    if (line[comma + 1] != ',') values[line.substr(0, comma)] = std::stod(line.substr(comma + 1));  // else not recorded
  }
  return values;
}

TEST(Cli, SeriesWithStoppedRunsFitsBetaAndTheDepthDecay)
{
  auto dir = testing::scratch_dir();
  const double beta = kPouliquenBeta, ell = kPouliquenEll;
  write_pouliquen_series(dir);
  auto outcome = cdpost("series " + (dir / "series.csv").string() + " --out " + (dir / "post").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const auto fits = dir / "post/fits.csv";
  // The runs measure U within 1.5 % (the stationarity criterion's drift) and h within 0.1 d: I, and
  // with it beta at a given l, within 2 %; the fit's own error adds three sigma.
  auto error_of = [&](const std::string& name) {
    std::istringstream lines(slurp(fits));
    std::string line;
    while (std::getline(lines, line))
      if (line.rfind(name + ",", 0) == 0) return std::stod(line.substr(line.find(',', name.size() + 1) + 1));
    ADD_FAILURE() << "no error of " << name;
    return 0.0;
  };
  EXPECT_NEAR(csv_value(fits, "pouliquen_betafree_beta_mu0.5"), beta,
              3 * error_of("pouliquen_betafree_beta_mu0.5") + 0.02 * beta);
  EXPECT_NEAR(csv_value(fits, "pouliquen_betafree_ell_mu0.5"), ell,
              3 * error_of("pouliquen_betafree_ell_mu0.5") + 0.02 * ell);
  EXPECT_EQ(csv_value(fits, "pouliquen_betafree_stopped_runs_mu0.5"), 3);
  EXPECT_EQ(line_count(slurp(dir / "post/runs.csv")), 8u);
  const auto residuals = slurp(dir / "post/residuals.csv");
  EXPECT_NE(residuals.find("\nstopped21.5,0.5,21.5,pouliquen_betafree,tan_theta,"), std::string::npos) << residuals;
  // Surface definition: pouliquen, betafree (5 + 3) at mu 0.5; muI, phi_U, phi_I over all. Packing definition (the
  // runs have packing.chunk): the same but betafree.
  EXPECT_EQ(line_count(residuals), 1u + (5 + 8 + 7 + 7 + 7) + (5 + 7 + 7 + 7));
  // Both definitions see h = 40 d (2 <z> and the half height of phi(z)): the same rule at fixed beta.
  EXPECT_NEAR(csv_value(fits, "packing_pouliquen_ell_mu0.5"), csv_value(fits, "pouliquen_ell_mu0.5"),
              0.03 * csv_value(fits, "pouliquen_ell_mu0.5"));
  EXPECT_NEAR(csv_value(fits, "packing_phi_c_mu0.5"), testing::SyntheticRun{}.phi_bulk, 1e-6);
  EXPECT_EQ(line_count(slurp(dir / "post/layer_amplitudes.csv")), 1u + 7 * 5);  // 5 filled layers per run
  const auto json = slurp(dir / "post/fits.json");
  EXPECT_NE(json.find("correlation of A with U (mu = 2): 2 runs, no correlation or p-value (they need 3)"),
            std::string::npos);
  EXPECT_EQ(slurp(fits).find("correlation_A_U_p_value_mu2"), std::string::npos);
  EXPECT_NE(json.find("correlation of f with L not fitted: correlation is undefined: one of the series is constant"),
            std::string::npos);
  EXPECT_EQ(slurp(fits).find("correlation_f_L"), std::string::npos);
  for (const char* figure : {"amplitude_vs_depth", "pouliquen_beta_free"})
    EXPECT_TRUE(std::filesystem::exists(dir / "post/figures" / (std::string(figure) + ".png"))) << figure;
  // The layers' white noise (0.1 sqrt(g d) a sample) reads about 0.008 in a 1 Hz bin; added in
  // quadrature to the deepest layers' amplitude it lengthens lambda by about 0.3 d: 1 d allowed.
  std::istringstream decay(slurp(dir / "post/depth_decay.csv"));
  std::string line;
  std::getline(decay, line);
  EXPECT_EQ(line, "run,mu,theta_deg,decay_length_d,decay_length_error_d,layers,log_rms_residual");
  int rows = 0;
  while (std::getline(decay, line)) {
    ++rows;
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string field; std::getline(fields, field, ',');) f.push_back(field);
    ASSERT_EQ(f.size(), 7u) << line;
    EXPECT_NEAR(std::stod(f[3]), 20, 3 * std::stod(f[4]) + 1.0) << line;
    EXPECT_GE(std::stoi(f[5]), 3)
        << line;  // layers 5 ... 35 d; the top one ends at the surface h = 40 d, the measured h may cut it
  }
  EXPECT_EQ(rows, 7);

  std::ofstream(dir / "bad.csv") << "run,mu,theta,stopped,h_stop\nrun1,0.5,21,0,12\n";
  auto bad = cdpost("series " + (dir / "bad.csv").string());
  EXPECT_EQ(bad.err, "cdpost: error: " + (dir / "bad.csv").string() +
                         ":2: h_stop is given for a run that did not stop (stopped is not 1)\n");
  std::ofstream(dir / "bad.csv") << "run,mu,theta,stopped\nrun1,0.5,21,1\n";
  bad = cdpost("series " + (dir / "bad.csv").string());
  EXPECT_EQ(bad.err, "cdpost: error: " + (dir / "bad.csv").string() +
                         ":2: a stopped run needs its deposit thickness in the column h_stop (d)\n");
}

// A cell-length series: one friction and one angle, the amplitude of the oscillation falling as
// L^(-1/2). No flow rule is fitted to runs at one angle; A against L gives the exponent.
TEST(Cli, SeriesAtOneAngleGivesTheLengthLawAndNoFlowRule)
{
  auto dir = testing::scratch_dir();
  std::ofstream manifest(dir / "series.csv");
  manifest << "run,mu,theta,L\n";
  int index = 0;
  for (double length : {12.0, 22.0, 45.0, 90.0}) {
    testing::SyntheticRun run;
    run.duration = 2.5;
    run.relaxation = 0.1;
    run.with_chunks_and_dump = false;
    run.seed = static_cast<unsigned>(++index);
    run.noise = 0.05;  // about 0.004 in a 1 Hz bin against amplitudes of 0.07 to 0.2
    run.amplitude = 0.2 * std::pow(length / 12, -0.5);
    const std::string name = "L" + std::to_string(index);
    testing::write_synthetic_run(dir / name, run);
    manifest << name << ",0.5,22," << length << "\n";
  }
  manifest.close();
  auto outcome = cdpost("series " + (dir / "series.csv").string() + " --out " + (dir / "post").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const auto fits = slurp(dir / "post/fits.csv");
  EXPECT_EQ(fits.find("pouliquen_"), std::string::npos) << fits;
  EXPECT_EQ(fits.find("muI_"), std::string::npos) << fits;
  const auto json = slurp(dir / "post/fits.json");
  EXPECT_NE(json.find("Pouliquen's rule needs runs at 3 or more angles per friction coefficient; mu = 0.5 has 1"),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("the mu(I) rule: the runs at mu = 0.5 (1 angle(s)) are left out"), std::string::npos) << json;
  const auto values = csv_values(dir / "post/fits.csv");
  EXPECT_NEAR(values.at("A_vs_L_exponent"), -0.5, 0.05);
  EXPECT_NEAR(values.at("f_vs_L_exponent"), 0.0, 0.05);  // one frequency at every length
  EXPECT_EQ(values.at("correlation_A_L_n"), 4);
}

// The runs as `cdpost run` publishes them (results.csv, layers.csv: what results/runs/<name>
// keeps) give the series the same fits as their raw outputs, to the 10 digits written.
TEST(Cli, SeriesFromPublishedRunsGivesTheSameFits)
{
  auto dir = testing::scratch_dir();
  write_pouliquen_series(dir);
  auto raw = cdpost("series " + (dir / "series.csv").string() + " --out " + (dir / "post").string());
  ASSERT_EQ(raw.status, 0) << raw.err;
  std::ofstream manifest(dir / "published.csv");
  std::istringstream rows(slurp(dir / "series.csv"));
  std::string row;
  while (std::getline(rows, row)) {
    if (row.rfind("run", 0) == 0 && row.rfind("run,", 0) != 0) {
      const auto name = row.substr(0, row.find(','));
      auto published = cdpost("run " + (dir / name).string() + " --out " + (dir / "published" / name).string());
      ASSERT_EQ(published.status, 0) << published.err;
      row = "published/" + row;
    }
    manifest << row << "\n";
  }
  manifest.close();
  // The runs have packing.chunk: their published profile.csv carries phi(z), read back for the packing definition.
  EXPECT_EQ(slurp(dir / "published/run1/profile.csv").rfind("z_d,u_sqrt_gd,count,phi\n", 0), 0u);
  auto read = cdpost("series " + (dir / "published.csv").string() + " --out " + (dir / "post2").string());
  ASSERT_EQ(read.status, 0) << read.err;
  const auto expected = csv_values(dir / "post/fits.csv"), found = csv_values(dir / "post2/fits.csv");
  ASSERT_GT(expected.size(), 20u);
  ASSERT_EQ(found.size(), expected.size());
  for (const auto& [name, value] : expected) {
    ASSERT_EQ(found.count(name), 1u) << name;
    // Ten digits written; a correlation with the nearly constant phi amplifies their rounding
    // by about phi over its spread (~1e4).
    EXPECT_NEAR(found.at(name), value, 1e-5 * std::max(1.0, std::abs(value))) << name;
  }
  auto amplitudes = slurp(dir / "post2/layer_amplitudes.csv");
  for (size_t at; (at = amplitudes.find("published/")) != std::string::npos;) amplitudes.erase(at, 10);
  EXPECT_EQ(amplitudes, slurp(dir / "post/layer_amplitudes.csv"));

  // A malformed published file fails with its file and line.
  const auto results = dir / "published/run3/results.csv";
  auto text = slurp(results);
  const auto u_row = text.find("\nU,");
  text.replace(u_row + 3, text.find(',', u_row + 3) - (u_row + 3), "fast");
  std::ofstream(results) << text;
  auto bad = cdpost("series " + (dir / "published.csv").string() + " --out " + (dir / "post3").string());
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find(results.string() + ":"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("U"), std::string::npos) << bad.err;
  std::ofstream(results) << "name,value,error,unit,description\nU,1,,sqrt(g d),\"unterminated\n";
  bad = cdpost("series " + (dir / "published.csv").string() + " --out " + (dir / "post3").string());
  EXPECT_NE(bad.err.find(results.string() + ":2: unterminated quoted field"), std::string::npos) << bad.err;
  std::filesystem::copy_file(dir / "published/run2/results.csv", results,
                             std::filesystem::copy_options::overwrite_existing);
  const auto layers = dir / "published/run3/layers.csv";
  std::ofstream(layers) << "z_d,f_peak_Hz\n1,2\n";
  bad = cdpost("series " + (dir / "published.csv").string() + " --out " + (dir / "post3").string());
  EXPECT_NE(bad.err.find(layers.string() + ":1: expected the header z_d, f_peak_Hz"), std::string::npos) << bad.err;
}

// Rows of a CSV with a header: one map of column -> text per row.
std::vector<std::map<std::string, std::string>> csv_rows(const std::filesystem::path& csv)
{
  std::istringstream lines(slurp(csv));
  auto fields = [](const std::string& line) {
    std::vector<std::string> cells;
    std::istringstream cells_of(line + ",");  // a trailing empty field is a field
    for (std::string cell; std::getline(cells_of, cell, ',');) cells.push_back(cell);
    return cells;
  };
  std::string line;
  std::getline(lines, line);
  const auto header = fields(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(lines, line)) {
    const auto cells = fields(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (size_t c = 0; c < std::min(cells.size(), header.size()); ++c) row[header[c]] = cells[c];
    rows.push_back(row);
  }
  return rows;
}

// Two series compared: the Pouliquen series (a) and the same runs without run2 and run6 (b, so
// that its fits differ). Each series' fits in the comparison are those of `cdpost series` on it
// alone; the difference is (b - a) over the combined error; the figures draw both.
TEST(Cli, SeriesComparedWithAnotherKeepsEachOnesFits)
{
  auto dir = testing::scratch_dir();
  std::filesystem::create_directories(dir / "a");
  std::filesystem::create_directories(dir / "b");
  write_pouliquen_series(dir / "a");
  std::ofstream manifest(dir / "b/series.csv");
  std::istringstream rows(slurp(dir / "a/series.csv"));
  std::string row;
  while (std::getline(rows, row))
    if (row.rfind("run2,", 0) != 0 && row.rfind("run6,", 0) != 0)
      manifest << (row.rfind("run,", 0) == 0 ? "" : "../a/") << row << "\n";
  manifest.close();
  for (const char* series : {"a", "b"}) {
    const auto alone =
        cdpost("series " + (dir / series / "series.csv").string() + " --out " + (dir / series / "post").string());
    ASSERT_EQ(alone.status, 0) << alone.err;
  }
  auto compared = cdpost("series " + (dir / "a/series.csv").string() + " --compare " + (dir / "b/series.csv").string() +
                         " --out " + (dir / "compared").string());
  ASSERT_EQ(compared.status, 0) << compared.err;
  EXPECT_NE(compared.err.find("cdpost: warning: b: "), std::string::npos) << compared.err;
  // The labels are the manifests' folders.
  EXPECT_EQ(slurp(dir / "compared/compared_fits.csv").rfind("name,unit,a,a_error,b,b_error,difference_sigma\n", 0), 0u);
  const auto table = csv_rows(dir / "compared/compared_fits.csv");
  const auto alone_a = csv_values(dir / "a/post/fits.csv"), alone_b = csv_values(dir / "b/post/fits.csv");
  size_t in_a = 0, in_b = 0, differences = 0;
  for (const auto& fit : table) {
    const auto& name = fit.at("name");
    for (auto [label, alone, count] : {std::tuple{"a", &alone_a, &in_a}, std::tuple{"b", &alone_b, &in_b}}) {
      ASSERT_EQ(fit.at(label).empty(), alone->count(name) == 0) << label << " " << name;
      if (fit.at(label).empty()) continue;
      ++*count;
      EXPECT_NEAR(std::stod(fit.at(label)), alone->at(name), 1e-9 * std::abs(alone->at(name))) << name;
    }
    if (fit.at("difference_sigma").empty()) continue;
    ++differences;
    const double a = std::stod(fit.at("a")), b = std::stod(fit.at("b"));
    const double ea = std::stod(fit.at("a_error")), eb = std::stod(fit.at("b_error"));
    // a and b are written to 10 digits: their difference to about 1e-10 (|a| + |b|).
    const double rounding = 1e-9 * (std::abs(a) + std::abs(b)) / std::hypot(ea, eb);
    EXPECT_NEAR(std::stod(fit.at("difference_sigma")), (b - a) / std::hypot(ea, eb), rounding + 1e-9) << name;
  }
  EXPECT_EQ(in_a, alone_a.size());
  EXPECT_EQ(in_b, alone_b.size());
  EXPECT_GT(differences, 20u);
  // The comparison's report states the solver's health of each series' runs.
  const auto compared_report = slurp(dir / "compared/report.md");
  for (const char* label : {"a", "b"})
    EXPECT_NE(compared_report.find("## Solver health of the runs of " + std::string(label) +
                                   "\n\nFrom each run's solver.time"),
              std::string::npos)
        << label;
  // Both series on the same axes: per friction one colour (line type 1 for mu = 0.5), per series
  // a point type (circles, squares) and a dash (b dashed).
  const auto script = slurp(dir / "compared/figures/U_vs_theta.gp");
  EXPECT_NE(script.find("with yerrorbars pt 7 lt 1 title 'a: mu = 0.5'"), std::string::npos) << script.substr(0, 3000);
  EXPECT_NE(script.find("with yerrorbars pt 5 lt 1 title 'b: mu = 0.5'"), std::string::npos);
  EXPECT_NE(script.find("with lines lw 2 lt 1 dt 2 notitle"), std::string::npos);
  EXPECT_NE(script.find("with lines lw 2 lt 1 notitle"), std::string::npos);
  for (const char* figure : {"U_vs_theta", "phi_vs_U", "phi_vs_I", "f_vs_scale", "f_vs_shear_rate", "A_vs_phi"})
    EXPECT_TRUE(std::filesystem::exists(dir / "compared/figures" / (std::string(figure) + ".png"))) << figure;
  EXPECT_NE(slurp(dir / "compared/report.md").find("| `pouliquen_ell_mu0.5` |"), std::string::npos);

  // A manifest that does not exist or lists no runs, and labels that cannot name two series.
  const auto series_a = "series " + (dir / "a/series.csv").string() + " --out " + (dir / "bad").string();
  auto bad = cdpost(series_a + " --compare " + (dir / "none.csv").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(bad.err, "cdpost: error: " + (dir / "none.csv").string() + ": cannot open (no such file)\n");
  std::ofstream(dir / "empty.csv") << "run,mu,theta\n";
  bad = cdpost(series_a + " --compare " + (dir / "empty.csv").string());
  EXPECT_EQ(bad.err, "cdpost: error: " + (dir / "empty.csv").string() + ":1: no runs listed\n");
  bad = cdpost(series_a + " --compare " + (dir / "b/series.csv").string() + " --labels count");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(line_count(bad.err), 1u);
  EXPECT_NE(bad.err.find("--labels takes two names separated by one comma, not 'count'"), std::string::npos);
  bad = cdpost(series_a + " --compare " + (dir / "a/series.csv").string());
  // One folder, one file name: no default labels.
  EXPECT_NE(bad.err.find("both series are labelled 'series': give --labels A,B"), std::string::npos) << bad.err;
  bad = cdpost(series_a + " --labels count,layer");
  EXPECT_NE(bad.err.find("--labels names the series of --compare"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
}

}  // namespace
}  // namespace cdpost
