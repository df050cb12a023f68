// A run's solver health, which every report states: counted from solver.time's interval means
// and the log's solver lines, and "not recorded" (never left out, never a number) without them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/published_run.h"
#include "analysis/solver_health.h"
#include "io/line_source.h"
#include "lammps_text.h"
#include "temp_files.h"

namespace cdpost {
namespace {

const std::vector<std::string> kColumns = {"TimeStep", "f_cd[1]", "f_cd[2]", "f_cd[5]", "f_cd[7]"};

std::string slurp(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string error_of(const std::function<void()>& action)
{
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SolverHealth, CountsUnconvergedStepsFromTheIntervalMeans)
{
  const auto dir = testing::scratch_dir();
  // Three intervals of 100 steps: all converged, 90 %, half; sweeps 10, 20, 400.
  testing::write_file(dir / "solver.time", testing::ave_time_text(kColumns, {{100, 10, 1e-3, 0.001, 1},
                                                                             {200, 20, 1e-3, 0.002, 0.9},
                                                                             {300, 400, 1e-3, 0.0005, 0.5}}));
  testing::write_file(dir / "log.lammps",
                      "Fix contact/dynamics cd solver: 5539 steps, 111 unconverged (2 %), largest final norm 0.01, "
                      "sweeps per step median 71, 99th percentile 358, max 692, 0 rescued from a stall\n"
                      "Fix contact/dynamics cd solver: 0 steps, 0 unconverged (0 %), largest final norm 0, sweeps "
                      "per step median 0, 99th percentile 0, max 0, 0 rescued from a stall\n"
                      "SOLVER max_sweeps_per_step 837 max_interpenetration_d 6.5e-03\n");
  const auto record = read_solver_record(dir.string());
  ASSERT_TRUE(record.health);
  EXPECT_EQ(record.health->steps, 300);
  EXPECT_EQ(record.health->unconverged_steps, 60);
  EXPECT_DOUBLE_EQ(record.health->unconverged_fraction, 0.2);
  EXPECT_EQ(record.health->sweeps_median, 20);
  EXPECT_EQ(record.health->sweeps_p99, 400);
  EXPECT_EQ(record.health->overlap_max_d, 0.002);
  ASSERT_EQ(record.log_lines.size(), 1u);  // the "run 0" line left out
  EXPECT_EQ(record.log_lines[0].rfind("5539 steps, 111 unconverged", 0), 0u);
  EXPECT_EQ(record.largest_overlap_d, 6.5e-3);
  ResultTable results;
  add_solver_results(results, record);
  ASSERT_NE(results.find("solver_unconverged_fraction"), nullptr);
  EXPECT_DOUBLE_EQ(results.find("solver_unconverged_fraction")->value, 0.2);
  EXPECT_EQ(results.find("solver_sweeps_largest")->value, 837);
  // Step by step, the log's last run: its solver line's numbers.
  EXPECT_EQ(results.find("solver_log_unconverged_steps")->value, 111);
  EXPECT_EQ(results.find("solver_log_sweeps_median")->value, 71);
  EXPECT_EQ(results.find("solver_log_sweeps_p99")->value, 358);
  EXPECT_EQ(results.find("solver_log_sweeps_max")->value, 692);
  const auto text = solver_health_text(record);
  EXPECT_NE(text.find("60 of 300 steps unconverged (20 %)"), std::string::npos) << text;
  EXPECT_NE(text.find("\n1. 5539 steps, 111 unconverged"), std::string::npos) << text;
}

TEST(SolverHealth, AbsentFilesAreSaidNotRecordedInEveryOutput)
{
  const auto dir = testing::scratch_dir();
  const auto record = read_solver_record(dir.string());
  EXPECT_FALSE(record.health);
  const auto text = solver_health_text(record);
  EXPECT_NE(text.find("sweeps per step and the largest interpenetration: not recorded (no "), std::string::npos);
  EXPECT_NE(text.find("solver lines: not recorded"), std::string::npos) << text;
  ResultTable results;
  results.add("U", 1.5, "sqrt(g d)", "mean velocity");
  add_solver_results(results, record);
  EXPECT_EQ(results.find("solver_unconverged_steps"), nullptr);  // no number to compute with
  EXPECT_NE(results.markdown().find("| `solver_unconverged_steps` | not recorded |"), std::string::npos);
  EXPECT_NE(results.markdown().find("| `solver_log_sweeps_p99` | not recorded |"), std::string::npos);
  EXPECT_NE(results.text().find("solver_overlap_max"), std::string::npos);
  results.write_csv((dir / "results.csv").string());
  results.write_json((dir / "results.json").string(), {});
  EXPECT_NE(slurp(dir / "results.csv").find("\nsolver_unconverged_steps,,,"), std::string::npos);
  EXPECT_NE(slurp(dir / "results.json").find("{\"name\": \"solver_unconverged_steps\", \"value\": null"),
            std::string::npos);
  // Read back as a published run: still there, still not recorded.
  const auto published = read_published_run(dir.string());
  EXPECT_EQ(published.results.find("solver_unconverged_steps"), nullptr);
  EXPECT_EQ(published.results.rows().size(), results.rows().size());
  EXPECT_FALSE(published.results.rows().back().recorded);
  EXPECT_DOUBLE_EQ(published.results.find("U")->value, 1.5);
}

TEST(SolverHealth, BadFilesAreOneLineNamingFileAndLine)
{
  const auto dir = testing::scratch_dir();
  const auto path = testing::write_file(
      dir / "solver.time", testing::ave_time_text(kColumns, {{100, 10, 1e-3, 0.001, 1}, {200, 20, 1e-3, 0.002, 1.5}}));
  EXPECT_EQ(error_of([&] { read_solver_record(dir.string()); }),
            path + ":4: fraction of converged steps 1.5 is not in [0, 1]");
  // A solver.time of another layout gives no health, and says why; read as one of the fix's, it
  // is one line naming the missing column.
  testing::write_file(path, testing::ave_time_text({"TimeStep", "f_cd[1]"}, {{100, 10}}));
  const SolverRecord other_layout = read_solver_record(dir.string());
  EXPECT_FALSE(other_layout.health);
  EXPECT_EQ(other_layout.no_health_why, path + " holds no fix outputs 1, 5 and 7");
  EXPECT_EQ(error_of([&] { solver_health(read_ave_time(path)); }),
            path + ": no column f_ID[5] (fix contact/dynamics output 5) among TimeStep, f_cd[1]");
  testing::write_file(path, testing::ave_time_text(kColumns, {{200, 10, 1e-3, 0.001, 1}, {100, 10, 1e-3, 0.001, 1}}));
  EXPECT_EQ(error_of([&] { read_solver_record(dir.string()); }),
            path + ":4: TimeStep 100 does not increase (overlapping restart output?)");
}

}  // namespace
}  // namespace cdpost
