// A run whose step followed the flow (fix contact/dynamics dt_max) halved its step for a while:
// it wrote extra samples between the uniform ones (it samples every N steps) and its TimeStep
// no longer gives the time. cdpost keeps the uniform samples, an exact decimation, and maps
// TimeStep to time through the time file: every result is that of the same run sampled
// uniformly, to rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/run_analysis.h"
#include "io/ave_chunk.h"
#include "io/ave_time.h"
#include "io/line_source.h"
#include "synthetic_run.h"

namespace cdpost {
namespace {

constexpr long steps_per_sample = 100;  // sample k is at k ms, 100 k original steps

// Samples [first, first + count) where the step is halved: one more step per original step.
struct RefinedStretch {
  long first = 2000, count = 1000;  // by default between 2 s and 3 s

  long refined_step(long uniform_step) const
  {
    return uniform_step + std::clamp(uniform_step - first * steps_per_sample, 0L, count * steps_per_sample);
  }
  bool contains(long uniform_step) const
  {
    return uniform_step >= first * steps_per_sample && uniform_step < (first + count) * steps_per_sample;
  }
};

// The same flow.time with the halved stretch: TimeStep shifted and a sample between every two
// (its values anything: here the row's own, tripled).
void refine_time_file(const std::filesystem::path& from, const std::filesystem::path& to,
                      const RefinedStretch& stretch = {})
{
  const ColumnTable table = read_ave_time(from.string());
  std::vector<std::vector<double>> rows;
  for (size_t r = 0; r < table.rows(); ++r) {
    std::vector<double> row;
    for (const auto& column : table.columns) row.push_back(column[r]);
    const long step = static_cast<long>(row[0]);
    row[0] = static_cast<double>(stretch.refined_step(step));
    rows.push_back(row);
    if (!stretch.contains(step)) continue;
    std::vector<double> between = row;
    for (size_t c = 2; c < between.size(); ++c) between[c] *= 3;
    between[0] += steps_per_sample;                                                    // 100 half steps later
    between[1] += 0.5 * steps_per_sample * table.columns[1][1] / table.columns[0][1];  // half a sample
    rows.push_back(between);
  }
  testing::write_file(to, testing::ave_time_text(table.names, rows));
}

void refine_chunk_file(const std::filesystem::path& from, const std::filesystem::path& to, bool every_sample)
{
  const RefinedStretch stretch;
  const ChunkSeries chunks = read_ave_chunk(from.string());
  std::vector<long> steps;
  std::vector<size_t> source_block;
  for (size_t b = 0; b < chunks.blocks(); ++b) {
    const long step = static_cast<long>(chunks.timesteps[b]);
    steps.push_back(stretch.refined_step(step));
    source_block.push_back(b);
    if (every_sample && stretch.contains(step)) {
      steps.push_back(stretch.refined_step(step) + steps_per_sample);
      source_block.push_back(chunks.blocks());  // an extra sample
    }
  }
  testing::write_file(to,
                      testing::ave_chunk_text(chunks.names, steps, chunks.chunks, [&](size_t b, size_t c, size_t k) {
                        const size_t source = source_block[b];
                        if (source < chunks.blocks()) return chunks.value(source, c, k);
                        return 3 * chunks.value(source_block[b - 1], c, k);
                      }));
}

TEST(RefinedStep, ExtraSamplesAndShiftedStepsLeaveEveryResultUnchanged)
{
  const auto uniform = testing::scratch_dir() / "uniform", refined = testing::scratch_dir() / "refined";
  testing::SyntheticRun truth;
  testing::write_synthetic_run(uniform, truth);
  testing::write_synthetic_run(refined, truth);
  refine_time_file(uniform / "flow.time", refined / "flow.time");
  refine_chunk_file(uniform / "layers.chunk", refined / "layers.chunk", true);
  refine_chunk_file(uniform / "profile.chunk", refined / "profile.chunk", false);

  RunSettings settings;
  settings.directory = uniform.string();
  const RunAnalysis expected = analyse_run(settings);
  settings.directory = refined.string();
  const RunAnalysis got = analyse_run(settings);

  ASSERT_EQ(got.series.rows_read, expected.series.rows_read + RefinedStretch{}.count);
  ASSERT_EQ(got.series.time_s.size(), expected.series.time_s.size());
  for (const ResultRow& row : expected.results.rows()) {
    if (!row.recorded) continue;  // "not recorded" in both (the synthetic run has no log.lammps)
    const ResultRow* same = got.results.find(row.name);
    ASSERT_NE(same, nullptr) << row.name;
    EXPECT_NEAR(same->value, row.value, 1e-9 * (1 + std::abs(row.value))) << row.name;
  }
  ASSERT_EQ(got.layers.size(), expected.layers.size());
  for (size_t l = 0; l < got.layers.size(); ++l)
    EXPECT_NEAR(got.layers[l].peak.frequency_hz, expected.layers[l].peak.frequency_hz, 1e-9) << "layer " << l;
  EXPECT_TRUE(std::any_of(got.warnings.begin(), got.warnings.end(), [](const std::string& w) {
    return w.find("samples between the uniform ones") != std::string::npos;
  }));
}

// A file refined from end to end (a short continuation of a fast flow) shows no interval of
// the sample grid: its own rate, given as --sample-rate, brings back the uniform run's results;
// without it the spectrum reaches twice the frequency and A_mean, a mean over that wider band,
// differs.
TEST(RefinedStep, AFileRefinedThroughoutIsDecimatedToTheGivenRate)
{
  const auto uniform = testing::scratch_dir() / "uniform_all", refined = testing::scratch_dir() / "refined_all";
  testing::SyntheticRun truth;
  truth.with_chunks_and_dump = false;
  testing::write_synthetic_run(uniform, truth);
  testing::write_synthetic_run(refined, truth);
  refine_time_file(uniform / "flow.time", refined / "flow.time", RefinedStretch{0, 1000000});

  RunSettings settings;
  settings.directory = uniform.string();
  const RunAnalysis expected = analyse_run(settings);
  auto a_mean = [](const RunAnalysis& run) { return run.results.find("A_mean")->value; };
  settings.directory = refined.string();
  const RunAnalysis finer = analyse_run(settings);
  settings.sample_rate_hz = 1000;
  const RunAnalysis given = analyse_run(settings);

  EXPECT_EQ(given.series.time_s.size(), expected.series.time_s.size());
  EXPECT_NEAR(given.series.sample_interval_s, 1e-3, 1e-12);
  EXPECT_NEAR(a_mean(given), a_mean(expected), 1e-9 * a_mean(expected));
  EXPECT_NEAR(given.peak.frequency_hz, expected.peak.frequency_hz, 1e-9);
  EXPECT_NEAR(finer.series.sample_interval_s, 0.5e-3, 1e-12);
  EXPECT_GT(std::abs(a_mean(finer) - a_mean(expected)), 0.1 * a_mean(expected));

  settings.sample_rate_hz = 300;  // 3.3 ms: the 0.5 ms interval does not divide it
  EXPECT_THROW(analyse_run(settings), InputError);
  settings.sample_rate_hz = 4000;  // a grid finer than the file's samples
  EXPECT_THROW(analyse_run(settings), InputError);
}

}  // namespace
}  // namespace cdpost
