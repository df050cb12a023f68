// The along-cell analysis (signal/space_time, analysis/along_cell) on synthetic v(x, t) of known
// structure, and through the reader on a synthetic run folder with columns.chunk.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>

#include "analysis/along_cell.h"
#include "analysis/run_analysis.h"
#include "analysis/series_analysis.h"
#include "figures/along_cell_figures.h"
#include "figures/run_figures.h"
#include "figures/series_figures.h"
#include "synthetic_run.h"

namespace cdpost {
namespace {

constexpr double kDt = 1e-3;               // s: the deck's default sample rate
constexpr double kWidth = 1.5;             // d: the deck's default column width
constexpr double kReducedRate = 140.0714;  // sqrt(g/d) for d = 5e-4 m, g = 9.81 m/s^2 (Hz)

// v(x, t) of `columns` columns of kWidth: wave(x, t) plus white noise of its own in each column.
SpaceTimeField field_of(size_t columns, double duration_s, double noise,
                        const std::function<double(double x, double t)>& wave, unsigned seed = 3)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0, noise);
  SpaceTimeField field;
  field.sample_interval_s = kDt;
  field.cell_length = kWidth * columns;
  const auto samples = static_cast<size_t>(std::lround(duration_s / kDt));
  for (size_t j = 0; j < columns; ++j) {
    std::vector<double> v;
    for (size_t n = 0; n < samples; ++n) v.push_back(wave((j + 0.5) * kWidth, n * kDt) + gauss(rng));
    field.columns.push_back(v);
  }
  return field;
}

SpectralPeak peak_at(double frequency_hz, double half_width_hz)
{
  SpectralPeak peak;
  peak.frequency_hz = frequency_hz;
  peak.frequency_error_hz = half_width_hz;
  return peak;
}

struct Analysed {
  AlongCell along;
  ResultTable results;
  std::vector<std::string> warnings;
};

Analysed analyse(const SpaceTimeField& field, double frequency_hz, double half_width_hz)
{
  Analysed a;
  a.along = analyse_along_cell(field, peak_at(frequency_hz, half_width_hz), {}, kReducedRate, a.results, a.warnings);
  return a;
}

// (m, l) of the largest power at f > 0.
std::pair<int, size_t> strongest(const SpaceTimeSpectrum& s)
{
  std::pair<int, size_t> best{0, 1};
  for (int m = s.lowest_m(); m <= s.highest_m(); ++m)
    for (size_t l = 1; l < s.bins; ++l)
      if (s.power_at(m, l) > s.power_at(best.first, best.second)) best = {m, l};
  return best;
}

TEST(AlongCell, TravellingWavesLandAtTheirSignedWavenumberAndGiveTheirPhaseVelocity)
{
  const double f = 20, a = 0.5, L = 32 * kWidth;
  for (int m : {3, -2}) {
    const auto field =
        field_of(32, 10, 0.2, [&](double x, double t) { return a * std::cos(2 * M_PI * (m * x / L - f * t)); });
    const auto result = analyse(field, f, 1.0);
    const auto& s = result.along.spectrum;
    EXPECT_EQ(strongest(s), std::make_pair(m, size_t(20)));
    // A wave centred on a bin reads a^2 (power_at's normalisation); the noise adds ~1e-3.
    EXPECT_NEAR(s.power_at(m, 20), a * a, 0.02 * a * a);
    EXPECT_LT(s.power_at(-m, 20), 1e-2 * a * a);
    const auto& v = result.along.verdict;
    EXPECT_EQ(v.pattern, OscillationPattern::Travelling) << v.text;
    EXPECT_EQ(v.dominant_m, m);
    EXPECT_GT(std::abs(v.balance.value), 0.95);
    ASSERT_TRUE(result.along.phase_velocity);
    // f L / m in d/s, over sqrt(g/d): exact, since f is given exactly.
    EXPECT_NEAR(result.along.phase_velocity->value, f * L / m / kReducedRate, 1e-9);
    EXPECT_NE(v.text.find(m > 0 ? "along +x" : "along -x"), std::string::npos) << v.text;
  }
}

TEST(AlongCell, StandingWaveHasBalancedWavenumbers)
{
  const double f = 25, a = 0.5, L = 32 * kWidth;
  const auto field = field_of(32, 10, 0.05, [&](double x, double t) {
    return a * std::cos(2 * M_PI * 2 * x / L) * std::cos(2 * M_PI * f * t);
  });
  const auto result = analyse(field, f, 1.0);
  const auto& v = result.along.verdict;
  EXPECT_EQ(v.pattern, OscillationPattern::Standing) << v.text;
  EXPECT_EQ(std::abs(v.dominant_m), 2);
  EXPECT_LT(std::abs(v.balance.value), 0.05);  // the two halves a/2 cos(kx -+ wt) are equal
  // Each travelling half carries (a/2)^2.
  EXPECT_NEAR(result.along.spectrum.power_at(2, 25), a * a / 4, 0.02 * a * a);
  EXPECT_NEAR(result.along.spectrum.power_at(-2, 25), a * a / 4, 0.02 * a * a);
  EXPECT_FALSE(result.along.phase_velocity);
}

TEST(AlongCell, UniformOscillationIsCoherentEverywhere)
{
  const double f = 30, a = 0.3;
  const auto field = field_of(30, 10, 0.1, [&](double, double t) { return a * std::sin(2 * M_PI * f * t); });
  const auto result = analyse(field, f, 1.0);
  EXPECT_EQ(result.along.verdict.pattern, OscillationPattern::Uniform) << result.along.verdict.text;
  EXPECT_GT(result.along.verdict.uniform_fraction, 0.9);
  // Each column: signal a^2/2 against noise 0.01/1 Hz... coherence near 1 at every distance.
  for (double c : result.along.coherence.coherence) EXPECT_GT(c, 0.9);
  EXPECT_NEAR(result.along.spectrum.power_at(0, 30), a * a, 0.02 * a * a);
}

// Columns whose complex amplitudes at every frequency correlate as exp(-r / xi) (periodic r): a
// Gaussian field with that correlation matrix, each column a narrow-band process at f0.
SpaceTimeField correlated_field(size_t columns, double xi_d, double duration_s, unsigned seed)
{
  Eigen::MatrixXd correlation(columns, columns);
  for (size_t j = 0; j < columns; ++j)
    for (size_t k = 0; k < columns; ++k) {
      const size_t s = j > k ? j - k : k - j;
      correlation(j, k) = std::exp(-double(std::min(s, columns - s)) * kWidth / xi_d);
    }
  const Eigen::MatrixXd mix = Eigen::LLT<Eigen::MatrixXd>(correlation).matrixL();
  // Independent AR(2) processes resonating at 20 Hz (pole radius 0.99: a ~3 Hz wide line).
  const double radius = 0.99, omega = 2 * M_PI * 20 * kDt;
  const auto samples = static_cast<size_t>(std::lround(duration_s / kDt));
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  Eigen::MatrixXd independent(columns, samples);
  for (size_t j = 0; j < columns; ++j) {
    double previous = 0, before = 0;
    for (size_t n = 0; n < samples; ++n) {
      const double x = 2 * radius * std::cos(omega) * previous - radius * radius * before + gauss(rng);
      independent(j, n) = x;
      before = previous;
      previous = x;
    }
  }
  const Eigen::MatrixXd v = mix * independent;
  SpaceTimeField field;
  field.sample_interval_s = kDt;
  field.cell_length = kWidth * columns;
  for (size_t j = 0; j < columns; ++j) {
    field.columns.emplace_back(samples);
    for (size_t n = 0; n < samples; ++n) field.columns[j][n] = v(j, n);
  }
  return field;
}

TEST(AlongCell, RecoversAKnownCoherenceLength)
{
  // C(r) = exp(-2 r / xi) in expectation. Over 12 seeds of this 60 s field (119 segments, a
  // 5-bin band) the fitted xi scattered by 4.5 % (sd) about a mean 2.6 % low, its jackknife
  // error 5.7 % on average: the tolerance, 15 %, is over three times the scatter.
  const double xi = 6.0;
  for (unsigned seed : {1u, 2u}) {
    const auto result = analyse(correlated_field(32, xi, 60, seed), 20, 2.0);
    ASSERT_TRUE(result.along.fit) << (result.warnings.empty() ? "" : result.warnings.front());
    ASSERT_TRUE(result.along.fit->length);
    const auto& length = *result.along.fit->length;
    EXPECT_NEAR(length.value, xi, 0.15 * xi);
    EXPECT_GT(*length.error, 0.01 * xi);
    EXPECT_LT(*length.error, 0.1 * xi);
    EXPECT_NEAR(result.along.fit->short_range.value, 1.0, 0.05);  // no noise of the columns' own
    EXPECT_NEAR(result.along.fit->plateau.value, 0.0, 0.01);      // nothing coherent across the cell
    EXPECT_EQ(result.along.verdict.pattern, OscillationPattern::Local) << result.along.verdict.text;
    EXPECT_NEAR(result.along.coherence.coherence.front(), std::exp(-2 * kWidth / xi), 0.03);  // 0.61
  }
}

TEST(AlongCell, SeparatesAPartCoherentAcrossTheCellFromALocalOne)
{
  // A common process of power 1/4 in every column plus the local field of xi = 6 d of power 3/4:
  // coherency 1/4 + 3/4 exp(-r/xi), a plateau of C = 1/16. Tolerances as for the pure field.
  const double xi = 6.0;
  auto field = correlated_field(32, xi, 60, 4);
  const auto common = correlated_field(1, xi, 60, 5).columns.front();  // an independent process
  for (auto& column : field.columns)
    for (size_t n = 0; n < column.size(); ++n) column[n] = std::sqrt(0.75) * column[n] + 0.5 * common[n];
  const auto result = analyse(field, 20, 2.0);
  ASSERT_TRUE(result.along.fit && result.along.fit->length);
  EXPECT_NEAR(result.along.fit->length->value, xi, 0.15 * xi);
  EXPECT_NEAR(result.along.fit->plateau.value, 1.0 / 16, 0.02);
  EXPECT_EQ(result.along.verdict.pattern, OscillationPattern::Local) << result.along.verdict.text;
}

TEST(AlongCell, IncoherentColumnsSitAtTheNoiseFloorAndAreLocal)
{
  // Independent white columns: the expected coherence is the floor, 1 / (effective averages).
  // Over 30 s (59 segments, a 5-bin band) the mean over the 16 distances read 1.02 times the
  // floor; pairs sharing columns make that mean scatter by ~5 %: the tolerance is 15 %. (A band
  // across a peaked spectrum counts its bins as more independent than they are: an AR(2) line
  // 3 Hz wide in the same band read 1.16 times the floor.)
  const auto result = analyse(field_of(
                                  32, 30, 1.0, [](double, double) { return 0.0; }, 9),
                              20, 2.0);
  const auto& c = result.along.coherence;
  double mean = 0;
  for (double value : c.coherence) mean += value / double(c.coherence.size());
  EXPECT_NEAR(mean, c.noise_floor, 0.15 * c.noise_floor);
  EXPECT_EQ(result.along.verdict.pattern, OscillationPattern::Local) << result.along.verdict.text;
  EXPECT_NE(result.along.verdict.text.find("below one column width"), std::string::npos);
}

// The user trial's figure: a window of one segment reads coherence 1 between any columns (and a
// few averages near it), which once gave "local: no coherence even between neighbouring columns"
// beside numbers of 0.98. Too few averages resolve nothing: never local, and the text says so.
TEST(AlongCell, VerdictAgreesWithItsNumbersWhenTooFewAveragesResolveNothing)
{
  const double f = 30, a = 0.3;
  const auto field = field_of(16, 1, 0.02, [&](double, double t) { return a * std::sin(2 * M_PI * f * t); });
  const auto result = analyse(field, f, 0.1);
  const auto& c = result.along.coherence;
  ASSERT_LT(c.averages, 4);
  for (double value : c.coherence) EXPECT_GT(value, 0.9);
  const auto& v = result.along.verdict;
  EXPECT_EQ(v.pattern, OscillationPattern::Uniform) << v.text;
  EXPECT_EQ(v.text.find("no coherence"), std::string::npos) << v.text;
  EXPECT_NE(v.text.find("the coherence does not resolve where the oscillation lives"), std::string::npos) << v.text;

  // The same numbers judged directly: 0.98 at every distance from 2 averages is not local either.
  CoherenceByDistance reading;
  reading.distance = {1.5, 3, 4.5, 6};
  reading.coherence = {0.98, 0.98, 0.98, 0.98};
  reading.averages = 2;
  reading.noise_floor = 0.5;
  std::vector<double> power(17, 0.0);
  power[8] = 1;  // all at m = 0 (16 columns: m = -8..8)
  const auto judged = judge_pattern(power, 16, reading, std::nullopt, 24);
  EXPECT_NE(judged.pattern, OscillationPattern::Local) << judged.text;
  EXPECT_EQ(judged.text.find("no coherence"), std::string::npos) << judged.text;
  // With enough averages the same reading is coherent; a reading at the floor is local and says
  // its number against twice the floor.
  reading.averages = 20, reading.noise_floor = 0.05;
  EXPECT_EQ(judge_pattern(power, 16, reading, std::nullopt, 24).pattern, OscillationPattern::Uniform);
  reading.coherence = {0.06, 0.05, 0.05, 0.05};
  const auto local = judge_pattern(power, 16, reading, std::nullopt, 24);
  EXPECT_EQ(local.pattern, OscillationPattern::Local);
  EXPECT_NE(local.text.find("(0.06 at r = 1.5 d, below twice the noise floor 0.05)"), std::string::npos) << local.text;
}

TEST(AlongCell, CoherenceThatDoesNotDecayGivesAVerdictNotALength)
{
  // A uniform oscillation with noise of each column's own: C = 0.9974 at every distance (its
  // expectation is the same at all of them). No length, no warning, the verdict says why.
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    const double f = 30, a = 0.3;
    const auto field = field_of(
        30, 10, 0.1, [&](double, double t) { return a * std::sin(2 * M_PI * f * t); }, seed);
    const auto result = analyse(field, f, 1.0);
    EXPECT_FALSE(result.along.fit && result.along.fit->length);
    EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
    ASSERT_TRUE(result.along.decay);
    EXPECT_LT(result.along.decay->value,
              2 * result.along.decay->error.value_or(0) + result.along.coherence.noise_floor);
    EXPECT_NE(result.along.verdict.text.find("no coherence length: the coherence does not decay over the cell"),
              std::string::npos)
        << result.along.verdict.text;
    EXPECT_EQ(result.results.find("coherence_length"), nullptr);
  }
}

TEST(AlongCell, FittedCoherencesNeverExceedOne)
{
  // Measured coherences all below 1 that fall by 0.002 from the first distance on: the expected
  // estimate of coherencies g0 = 1.006, g_far = 0.995, xi = 1.5 d (g0 above 1: a field cannot
  // have it, but its curve is below 1 from r = 1.5 d on). Coherencies fitted as free numbers
  // extrapolate to c0 = 1.012 at r = 0; as magnitudes they stay at or below 1. The fall is below
  // the noise floor: no length.
  CoherenceByDistance coherence;
  coherence.noise_floor = 0.04;
  const double g0 = 1.006, g_far = 0.995, xi = 1.5;
  for (int s = 1; s <= 8; ++s) {
    const double r = 1.5 * s, gamma = g_far + (g0 - g_far) * std::exp(-r / xi), c = gamma * gamma;
    coherence.distance.push_back(r);
    coherence.coherence.push_back(c + (1 - c) * (1 - c) * coherence.noise_floor);
    ASSERT_LT(coherence.coherence.back(), 1.0);
  }
  for (int g = 0; g < 5; ++g) {  // leave-one-out curves scattered by 1e-4
    auto curve = coherence.coherence;
    for (size_t i = 0; i < curve.size(); ++i) curve[i] -= 1e-4 * std::sin(3.0 * g + double(i));
    coherence.without_group.push_back(curve);
  }
  const auto fit = fit_coherence(coherence);
  EXPECT_LE(fit.short_range.value, 1.0);
  EXPECT_LE(fit.plateau.value, 1.0);
  EXPECT_GT(fit.short_range.value, 0.99);
  EXPECT_NEAR(fit.plateau.value, g_far * g_far, 0.002);
  EXPECT_FALSE(fit.length);
  EXPECT_FALSE(coherence_decays(coherence));
}

TEST(AlongCell, BandCoversThePeakHalfWidthAndAtLeastOneBin)
{
  auto band = band_around(1.0, 501, 20.3, 4.8);
  EXPECT_EQ(band.first, 16u);
  EXPECT_EQ(band.last, 25u);
  band = band_around(1.0, 501, 20.3, 0.1);
  EXPECT_EQ(band.first, 20u);
  EXPECT_EQ(band.last, 20u);
}

TEST(AlongCell, UnequalColumnsAreRefusedAndTooFewLeaveNoFit)
{
  auto field = field_of(8, 1, 0.1, [](double, double) { return 0.0; });
  field.columns[3].pop_back();
  EXPECT_THROW(space_time_spectrum(field, {}), AnalysisError);
  const auto few = analyse(field_of(4, 4, 0.1, [](double, double) { return 0.0; }), 20, 1);
  EXPECT_FALSE(few.along.fit);
  ASSERT_EQ(few.warnings.size(), 1u);
  EXPECT_NE(few.warnings.front().find("needs 4 distances"), std::string::npos) << few.warnings.front();
  // A window of one segment has no jackknife: no fit, said in the report, not a warning.
  const auto short_window = analyse(field_of(8, 1, 0.1, [](double, double) { return 0.0; }), 20, 1);
  EXPECT_FALSE(short_window.along.fit);
  EXPECT_TRUE(short_window.warnings.empty());
  EXPECT_NE(along_cell_text(short_window.along, "stationary window").find("holds 1 segment(s)"), std::string::npos);
}

// Through the reader: a synthetic run folder with columns.chunk, the layer's oscillation in
// every column with noise of each column's own, one column empty every 40th sample.
class AlongCellRun : public ::testing::Test {
 protected:
  void SetUp() override
  {
    truth_.with_columns = true;
    truth_.duration = 8;
    settings_.cell_length_d = 45;
  }
  RunAnalysis analysed()
  {
    const auto dir = testing::scratch_dir() / "run";
    testing::write_synthetic_run(dir, truth_);
    settings_.directory = dir.string();
    return analyse_run(settings_);
  }
  testing::SyntheticRun truth_;
  RunSettings settings_;
};

TEST_F(AlongCellRun, UniformOscillationOfTheRunIsFoundThroughTheFile)
{
  const auto run = analysed();
  ASSERT_TRUE(run.along_cell) << (run.warnings.empty() ? "" : run.warnings.front());
  EXPECT_TRUE(run.warnings.empty()) << run.warnings.front();
  EXPECT_EQ(run.along_cell->verdict.pattern, OscillationPattern::Uniform) << run.along_cell->verdict.text;
  EXPECT_EQ(run.results.find("columns")->value, 30);
  EXPECT_DOUBLE_EQ(run.results.find("column_width")->value, 1.5);
  EXPECT_EQ(run.results.find("oscillation_pattern")->value, 1);
  // Column 3 is empty in every 40th sample of the window, interpolated.
  const double filled = run.results.find("column_samples_filled")->value;
  EXPECT_NEAR(filled, run.along_cell->spectrum.segments > 0 ? (run.window.end - run.window.begin) / 40.0 : 0, 1.5);
  // m = 0 of the columns is the layer's oscillation: power A^2 near the layer's peak.
  const auto& s = run.along_cell->spectrum;
  const size_t l = static_cast<size_t>(std::lround(truth_.frequency / s.resolution_hz));
  EXPECT_NEAR(std::sqrt(s.power_at(0, l)), truth_.amplitude, 0.1 * truth_.amplitude);
}

TEST_F(AlongCellRun, WithoutTheCellLengthOrTheFileOneLineSaysSo)
{
  settings_.cell_length_d.reset();
  auto run = analysed();
  EXPECT_FALSE(run.along_cell);
  ASSERT_EQ(run.warnings.size(), 1u);
  EXPECT_NE(run.warnings.front().find("--cell-length"), std::string::npos) << run.warnings.front();

  truth_.with_columns = false;
  settings_.cell_length_d = 45;
  const auto dir = testing::scratch_dir() / "without";
  testing::write_synthetic_run(dir, truth_);
  settings_.directory = dir.string();
  run = analyse_run(settings_);
  ASSERT_EQ(run.warnings.size(), 1u);
  EXPECT_NE(run.warnings.front().find("columns.chunk not found"), std::string::npos) << run.warnings.front();
  EXPECT_FALSE(run.results.find("oscillation_pattern"));
}

TEST_F(AlongCellRun, TooSparseAColumnIsNamed)
{
  truth_.empty_every = 10;  // 10 % of the samples: more than the 5 % that may be interpolated
  const auto run = analysed();
  EXPECT_FALSE(run.along_cell);
  ASSERT_EQ(run.warnings.size(), 1u);
  EXPECT_NE(run.warnings.front().find("column 3 is empty in 10"), std::string::npos) << run.warnings.front();
}

// A series of two raw runs (the manifest's L gives their cell length) and one published run
// (its results.csv as `cdpost run` wrote it): each gets its verdict and coherence columns.
TEST(AlongCellSeries, EveryRunGetsItsVerdictRawOrPublished)
{
  const auto dir = testing::scratch_dir();
  std::ofstream manifest(dir / "series.csv");
  manifest << "run,mu,theta,L\n";
  for (int i = 1; i <= 3; ++i) {
    testing::SyntheticRun run;
    run.with_columns = true;
    run.duration = 4;
    run.relaxation = 0.1;
    run.seed = static_cast<unsigned>(i);
    run.u_final = 5.0 + i;
    run.with_solver = i != 2;  // run 2 recorded none: its row says so
    run.unconverged_steps = i == 1 ? 12 : 0;
    const std::string name = "run" + std::to_string(i);
    testing::write_synthetic_run(dir / name, run);
    manifest << name << ",0.5," << 21 + i << ",45\n";
  }
  manifest.close();
  RunSettings published;
  published.directory = (dir / "run3").string();
  published.cell_length_d = 45;
  auto analysed = analyse_run(published);
  write_run_outputs(analysed, (dir / "run3").string(), "");  // results.csv at its top: read as published

  SeriesSettings settings;
  settings.manifest = (dir / "series.csv").string();
  auto series = analyse_series(settings);
  write_series_outputs(series, (dir / "post").string());
  std::ifstream csv(dir / "post/along_cell.csv");
  std::string line, text;
  int rows = 0;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("run,mu,theta_deg,pattern,coherence_length,coherence_length_error,", 0), 0u) << line;
  while (std::getline(csv, line)) ++rows, text += line + "\n";
  EXPECT_EQ(rows, 3);
  for (const char* run : {"run1,0.5,22,uniform,", "run2,0.5,23,uniform,", "run3,0.5,24,uniform,"})
    EXPECT_NE(text.find(run), std::string::npos) << text;
  // The series' report states each run's solver health, or that it was not recorded.
  std::ifstream report_file(dir / "post/report.md");
  const std::string report((std::istreambuf_iterator<char>(report_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("## Solver health of the runs"), std::string::npos);
  const auto table = report.substr(report.find("## Solver health of the runs"), 900);
  EXPECT_NE(report.find("| run1 (mu 0.5, 22 deg) | 12 of 390000 | 0.0030769 |"), std::string::npos) << table;
  EXPECT_NE(report.find("| run2 (mu 0.5, 23 deg) | not recorded | not recorded |"), std::string::npos) << report;
  EXPECT_NE(report.find("| run3 (mu 0.5, 24 deg) | 0 of 390000 |"), std::string::npos) << report;
  EXPECT_TRUE(std::filesystem::exists(dir / "post/figures/coherence_vs_U.png") ||
              std::filesystem::exists(dir / "post/figures/coherence_vs_U.gp"));
}

}  // namespace
}  // namespace cdpost
