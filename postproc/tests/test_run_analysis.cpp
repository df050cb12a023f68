#include <gtest/gtest.h>

#include "analysis/run_analysis.h"
#include "io/line_source.h"
#include "synthetic_run.h"

namespace cdpost {
namespace {

double result(const RunAnalysis& run, const std::string& name)
{
  const auto* row = run.results.find(name);
  if (!row) ADD_FAILURE() << "no result " << name;
  return row ? row->value : 0;
}
double error(const RunAnalysis& run, const std::string& name)
{
  const auto* row = run.results.find(name);
  return row && row->error ? *row->error : 0;
}

class SyntheticRunTest : public ::testing::Test {
 protected:
  void SetUp() override
  {
    dir_ = testing::scratch_dir() / "run";
    testing::write_synthetic_run(dir_, truth_);
    settings_.directory = dir_.string();
  }
  std::filesystem::path dir_;
  testing::SyntheticRun truth_;
  RunSettings settings_;
};

TEST_F(SyntheticRunTest, RecoversEveryMeasuredQuantity)
{
  auto run = analyse_run(settings_);
  EXPECT_TRUE(run.window_detected);
  EXPECT_TRUE(run.window_stationary);
  EXPECT_GT(result(run, "t_start") * std::sqrt(truth_.d / truth_.g), 3 * truth_.relaxation * 0.5);
  EXPECT_NEAR(result(run, "U"), truth_.u_final, 0.015 * truth_.u_final);  // the criterion allows a small drift
  EXPECT_NEAR(result(run, "phi"), truth_.phi, 4 * error(run, "phi") + 1e-3);
  EXPECT_NEAR(result(run, "h"), truth_.h, 0.1);
  EXPECT_NEAR(result(run, "f"), truth_.frequency, error(run, "f"));
  EXPECT_NEAR(result(run, "A"), truth_.amplitude, 0.25 * truth_.amplitude);
  EXPECT_LT(result(run, "A_mean"), 0.2 * truth_.amplitude);
  EXPECT_NEAR(result(run, "I"), truth_.u_final / std::pow(truth_.h, 1.5), 0.01 * result(run, "I"));
  EXPECT_NEAR(result(run, "shear_rate_reduced"), truth_.u_final / truth_.h, 0.01);
  EXPECT_NEAR(result(run, "creep_lambda"), truth_.creep_lambda, 3 * error(run, "creep_lambda") + 0.05);
  EXPECT_GT(result(run, "bagnold_r2"), 0.99);
  // phi(z) is the same in every block: its bulk and half-height come out exactly (to rounding).
  EXPECT_NEAR(result(run, "phi_bulk"), truth_.phi_bulk, 1e-9);
  EXPECT_NEAR(result(run, "h_packing"), truth_.h, 1e-6);
  EXPECT_NEAR(result(run, "I_packing"), result(run, "U") / std::pow(truth_.h, 1.5), 1e-9);
  ASSERT_EQ(run.profile->phi.size(), run.profile->z_d.size());
  EXPECT_NEAR(run.profile->phi.front(), truth_.phi_bed, 1e-9);
  ASSERT_EQ(run.layers.size(), 5u);  // the empty top layer is left out
  EXPECT_LT(run.layers.front().amplitude_at_f, run.layers.back().amplitude_at_f);
  EXPECT_TRUE(run.warnings.empty());
}

TEST_F(SyntheticRunTest, ExplicitWindowOverridesDetection)
{
  settings_.t_start = 0.0;
  auto run = analyse_run(settings_);
  EXPECT_FALSE(run.window_detected);
  EXPECT_EQ(run.window.begin, 0u);
  EXPECT_LT(result(run, "U"), truth_.u_final - 0.2);  // the transient drags the mean down
  // ... and U drifts across it: analysed all the same, labelled and warned of.
  EXPECT_FALSE(run.window_stationary);
  EXPECT_GT(result(run, "stationary_drift"), run.settings.criterion.max_relative_drift);
  ASSERT_EQ(run.warnings.size(), 1u);
  EXPECT_NE(run.warnings[0].find("is not stationary: U drifts by"), std::string::npos) << run.warnings[0];
  EXPECT_EQ(window_name(run), "window (not stationary)");
}

TEST_F(SyntheticRunTest, MissingTimeInformationIsAnErrorNamingTheFile)
{
  settings_.columns.time = "v_elapsed";
  try {
    analyse_run(settings_);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flow.time: no time column 'v_elapsed': give --dt"), std::string::npos)
        << e.what();
  }
  settings_.timestep_size = truth_.dt;
  EXPECT_NEAR(result(analyse_run(settings_), "f"), truth_.frequency, 1.0);
}

TEST_F(SyntheticRunTest, ReducedInputUnitsGiveTheSameNumbers)
{
  auto si = analyse_run(settings_);
  // Re-express the flow file in reduced units: time in sqrt(d/g), velocities in sqrt(g d).
  const double t0 = std::sqrt(truth_.d / truth_.g), v0 = truth_.v0();
  auto text = testing::ave_time_text({"TimeStep", "v_time", "v_u_flow", "v_v_flow"}, [&] {
    std::vector<std::vector<double>> rows;
    for (size_t i = 0; i < si.series.time_s.size(); ++i)
      rows.push_back(
          {double(i + 1), si.series.time_s[i] / t0, si.series.u_flow_mps[i] / v0, si.series.v_flow_mps[i] / v0});
    return rows;
  }());
  auto reduced_dir = testing::scratch_dir() / "reduced";
  std::filesystem::create_directories(reduced_dir);
  testing::write_file(reduced_dir / "flow.time", text);
  RunSettings reduced;
  reduced.directory = reduced_dir.string();
  reduced.units.use_reduced_input();
  auto run = analyse_run(reduced);
  EXPECT_NEAR(result(run, "U"), result(si, "U"), 1e-6);
  EXPECT_NEAR(result(run, "f"), result(si, "f"), 1e-6);
  EXPECT_NEAR(result(run, "A"), result(si, "A"), 1e-6);
  EXPECT_GE(run.warnings.size(), 3u);  // no u_all, phi, profile, layers: said, not silent
}

}  // namespace
}  // namespace cdpost
