// Unit tests of cdref's pieces on synthetic files: the ave/spatial conversion, overlaps from
// dumps, run.info and log parsing, collisions, and the comparison of synthetic run directories.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "collision.h"
#include "comparison.h"
#include "io/ave_chunk.h"
#include "io/line_source.h"
#include "overlaps.h"
#include "run_info.h"
#include "scratch.h"
#include "spatial_to_chunk.h"

namespace fs = std::filesystem;
using cdref::testing::dump_frame;
using cdref::testing::DumpDisk;
using cdref::testing::read_file;
using cdref::testing::scratch_dir;
using cdref::testing::write_file;

namespace {

// Expects `call` to throw an InputError whose message starts with "PATH:LINE:".
template <class Call>
void expect_input_error(Call call, const std::string& path, long line, const std::string& fragment)
{
  try {
    call();
    FAIL() << "no error for " << path;
  } catch (const cdpost::InputError& e) {
    const std::string where = line > 0 ? path + ":" + std::to_string(line) + ":" : path + ": ";
    EXPECT_EQ(std::string(e.what()).rfind(where, 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

const char* const spatial_text =
    "# Spatial-averaged data for fix layersout and group mobile\n"
    "# Timestep Number-of-bins\n"
    "# Bin Coord Ncount vy\n"
    "100 3\n"
    "  1 0.00125 16 0.5\n"
    "  2 0.00375 12.5 -0.25\n"
    "  3 0.00625 0 0\n"
    "200 3\n"
    "  1 0.00125 15 0.1\n"
    "  2 0.00375 13 0.2\n"
    "  3 0.00625 1 0.3\n";

}  // namespace

TEST(SpatialToChunk, ConvertsIntoAFileCdpostReads)
{
  auto dir = scratch_dir();
  auto in = write_file(dir / "layers.spatial", spatial_text);
  auto out = (dir / "layers.chunk").string();
  auto result = cdref::spatial_to_chunk(in, out);
  EXPECT_EQ(result.blocks, 2);
  EXPECT_EQ(result.bins, 3);
  auto chunks = cdpost::read_ave_chunk(out);
  ASSERT_EQ(chunks.blocks(), 2u);
  ASSERT_EQ(chunks.chunks, 3u);
  EXPECT_EQ(chunks.names, (std::vector<std::string>{"Coord1", "Ncount", "vy"}));
  EXPECT_DOUBLE_EQ(chunks.timesteps[1], 200);
  EXPECT_DOUBLE_EQ(chunks.value(0, 1, chunks.column_index("Ncount")), 12.5);
  EXPECT_DOUBLE_EQ(chunks.value(1, 2, chunks.column_index("vy")), 0.3);
  EXPECT_NE(read_file(out).find("100 3 28.5\n"), std::string::npos) << "total count of the first block";
}

TEST(SpatialToChunk, RefusesBrokenFilesNamingFileAndLine)
{
  auto dir = scratch_dir();
  const std::string text = spatial_text;
  struct Case {
    std::string name, text;
    long line;
    std::string fragment;
  };
  std::string wrong_bin = text;
  wrong_bin.replace(wrong_bin.find("  2 0.00375 12.5"), 3, "  4");
  std::string changed = text;
  changed.replace(changed.find("200 3"), 5, "200 2");
  std::vector<Case> cases = {
      {"truncated", text.substr(0, text.find("  3 0.00625 1 0.3")), 10, "file ends inside the block"},
      {"wrong-bin", wrong_bin, 6, "expected bin 2"},
      {"changed", changed, 8, "number of bins changed"},
      {"nan", std::string(text).replace(text.find("-0.25"), 5, "nan"), 6, "vy"},
      {"chunk-file",
       "# Chunk-averaged\n# Timestep Number-of-chunks Total-count\n# Chunk Coord1 Ncount vy\n100 1 3\n  1 0 3 0\n", 4,
       "no '# Bin"},
  };
  for (const auto& c : cases) {
    auto in = write_file(dir / (c.name + ".spatial"), c.text);
    expect_input_error([&] { cdref::spatial_to_chunk(in, (dir / (c.name + ".chunk")).string()); }, in, c.line,
                       c.fragment);
  }
}

TEST(Overlaps, PairsAcrossThePeriodicBoundaryAndTheFloor)
{
  auto dir = scratch_dir();
  const double d = 1.0;
  // Two disks overlapping by 0.02 across x = 0 = 10, one touching exactly, one 0.01 into the floor.
  std::vector<DumpDisk> disks = {{0.24, 5, 0.5}, {9.26, 5, 0.5}, {5, 5, 0.5}, {6, 5, 0.5}, {3, 0.49, 0.5}};
  auto path = write_file(dir / "dump", dump_frame(100, 0, 10, 0, 20, disks) + dump_frame(200, 0, 10, 0, 20, disks));
  cdref::OverlapOptions options;
  options.mean_diameter = d;
  auto s = cdref::dump_overlaps(path, options);
  EXPECT_EQ(s.frames, 2);
  EXPECT_EQ(s.contacts, 4);
  EXPECT_NEAR(s.mean, 0.015, 1e-12);
  EXPECT_NEAR(s.max, 0.02, 1e-12);
  options.first_timestep = 150;
  EXPECT_EQ(cdref::dump_overlaps(path, options).frames, 1);
  options.first_timestep = 300;
  expect_input_error([&] { cdref::dump_overlaps(path, options); }, path, 0, "no frame");
}

TEST(Overlaps, CellListAgreesWithAllPairs)
{
  auto dir = scratch_dir();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(0, 30), y(0, 12), r(0.4, 0.6);
  std::vector<DumpDisk> disks;
  for (int i = 0; i < 400; ++i) disks.push_back({x(rng), y(rng) + 0.6, r(rng)});
  auto path = write_file(dir / "dump", dump_frame(0, 0, 30, 0, 20, disks));
  cdref::OverlapOptions options;
  options.mean_diameter = 1.0;
  auto s = cdref::dump_overlaps(path, options);
  long contacts = 0;
  double sum = 0;
  for (size_t i = 0; i < disks.size(); ++i)
    for (size_t j = i + 1; j < disks.size(); ++j) {
      double dx = disks[i].x - disks[j].x;
      dx -= 30 * std::round(dx / 30);
      const double gap = std::hypot(dx, disks[i].y - disks[j].y) - disks[i].r - disks[j].r;
      if (gap < -1e-9) {
        ++contacts;
        sum -= gap;
      }
    }
  ASSERT_GT(contacts, 100);
  EXPECT_EQ(s.contacts, contacts);
  EXPECT_NEAR(s.mean, sum / contacts, 1e-12);
}

TEST(RunInfo, ReadsKeysAndRefusesMalformedLines)
{
  auto dir = scratch_dir();
  auto path = write_file(dir / "run.info", "code lammps-granular\nk_eff 1.5e5\n\nmodel hooke\n");
  auto info = cdref::read_run_info(path);
  EXPECT_EQ(info.text("code").value(), "lammps-granular");
  EXPECT_DOUBLE_EQ(info.number("k_eff").value(), 1.5e5);
  EXPECT_FALSE(info.number("f_contact"));
  EXPECT_THROW(info.number("model"), cdpost::InputError);
  EXPECT_TRUE(cdref::read_run_info((dir / "absent").string()).values.empty());
  auto bad = write_file(dir / "bad.info", "code lmp_cd\nmodel rigid disks\n");
  expect_input_error([&] { cdref::read_run_info(bad); }, bad, 2, "expected 'key value'");
  auto twice = write_file(dir / "twice.info", "dt 1\ndt 2\n");
  expect_input_error([&] { cdref::read_run_info(twice); }, twice, 2, "given twice");
}

TEST(RunInfo, LoopTimesOfLammpsAndLiggghtsLogs)
{
  auto dir = scratch_dir();
  auto lammps =
      write_file(dir / "log.lammps",
                 "Loop time of 3.25764 on 1 procs for 53617 steps with 420 atoms\n\n48.9% CPU use with 1 MPI tasks x 1 "
                 "OpenMP threads\n"
                 "Loop time of 9.5 on 1 procs for 1000 steps with 420 atoms\n\n99.1% CPU use with 1 MPI tasks\n");
  auto times = cdref::read_loop_times(lammps);
  ASSERT_EQ(times.size(), 2u);
  EXPECT_DOUBLE_EQ(times[0].seconds, 3.25764);
  EXPECT_EQ(times[0].steps, 53617);
  EXPECT_DOUBLE_EQ(times[0].cpu_percent.value(), 48.9);
  EXPECT_DOUBLE_EQ(times[1].cpu_percent.value(), 99.1);
  auto liggghts = write_file(
      dir / "log.liggghts",
      "Loop time of 2.46508 on 1 procs for 26808 steps with 420 atoms, finish time Sun Nov 22 04:36:33 2026\n");
  times = cdref::read_loop_times(liggghts);
  ASSERT_EQ(times.size(), 1u);
  EXPECT_EQ(times[0].steps, 26808);
  EXPECT_FALSE(times[0].cpu_percent);
}

TEST(Collision, RestitutionAndContactSteps)
{
  auto dir = scratch_dir();
  auto path = write_file(
      dir / "collision.txt",
      "# step gap normal_velocity\n0 1e-6 -1\n1 -1e-7 -0.9\n2 -2e-7 0.1\n3 -1e-7 0.4\n4 2e-8 0.5\n5 1e-7 0.5\n");
  auto c = cdref::analyse_collision(path);
  EXPECT_EQ(c.contact_steps, 3);
  EXPECT_DOUBLE_EQ(c.restitution, 0.5);
  EXPECT_DOUBLE_EQ(c.approach_speed, 1.0);
  auto open = write_file(dir / "open.txt", "0 1e-6 -1\n1 -1e-7 -0.5\n");
  expect_input_error([&] { cdref::analyse_collision(open); }, open, 0, "still in contact");
  auto receding = write_file(dir / "receding.txt", "0 1e-6 1\n");
  expect_input_error([&] { cdref::analyse_collision(receding); }, receding, 1, "do not approach");
}

namespace {

// A run directory as the decks write it (no time column, like LIGGGHTS): U(t) relaxing to
// `u` sqrt(g d); v(t) white noise plus a resonance at `tone_hz` of quality factor 5 (an AR(2)
// process driven by noise of `tone_amplitude`, as broad as a damped contact's), layers,
// profile, dump and a log with the flow stage's loop time.
struct FakeRun {
  std::string code = "lammps-granular", model = "hooke";
  double dt = 2e-5;       // s
  long sample_every = 5;  // steps: 10 kHz
  double duration = 1.0;  // s
  double u = 3.0, tone_hz = 1200, tone_amplitude = 0.02, noise = 0.01;
  std::optional<double> f_contact = 1000.0, k_reduced = 2e4;
  double overlap = 0.003;  // of the dump's overlapping pair, in d
  double loop_seconds = 20;
  unsigned seed = 1;
};

void write_fake_run(const fs::path& dir, const FakeRun& run)
{
  fs::create_directories(dir);
  const double d = 5e-4, v0 = std::sqrt(9.81 * d), ytop = 10 * d;
  std::ostringstream info;
  info << "code " << run.code << "\nmodel " << run.model << "\nd " << d << "\nbed_walls_d 10\ndt " << run.dt << "\n";
  if (run.f_contact)
    info << "f_contact " << *run.f_contact << "\nk_reduced " << *run.k_reduced << "\nk_eff " << *run.k_reduced * 9.63
         << "\noverlap_target 1e-3\n";
  write_file(dir / "run.info", info.str());
  std::mt19937 rng(run.seed);
  std::normal_distribution<double> gauss(0, 1);
  const long steps = static_cast<long>(run.duration / run.dt);
  const double fs = 1 / (run.dt * run.sample_every), pole = std::exp(-M_PI * run.tone_hz / 5 / fs);
  const double a1 = 2 * pole * std::cos(2 * M_PI * run.tone_hz / fs), a2 = -pole * pole;
  double r1 = 0, r2 = 0;  // the resonance's last two values
  std::ostringstream flow, layers, profile;
  flow.precision(10);
  flow << "# Time-averaged data for fix flowout\n# TimeStep v_u_all v_u_flow v_v_flow v_phi_flow v_h\n";
  layers << "# Chunk-averaged data\n# Timestep Number-of-chunks Total-count\n# Chunk Coord1 Ncount vy\n";
  profile << "# Chunk-averaged data\n# Timestep Number-of-chunks Total-count\n# Chunk Coord1 Ncount vx\n";
  for (long step = run.sample_every; step <= steps; step += run.sample_every) {
    const double t = step * run.dt;
    const double u = run.u * (1 - std::exp(-t / 0.1));
    const double resonance = a1 * r1 + a2 * r2 + run.tone_amplitude * gauss(rng);
    r2 = r1;
    r1 = resonance;
    const double v = resonance + run.noise * gauss(rng);
    flow << step << ' ' << 0.6 * u * v0 << ' ' << (u + 0.02 * gauss(rng)) * v0 << ' ' << v * v0 << ' '
         << 0.7 + 0.003 * gauss(rng) << ' ' << (10 + 0.1 * gauss(rng)) * d << '\n';
    layers << step << " 2 300\n  1 " << ytop - 2.5 * d << " 150 " << 0.1 * v * v0 << "\n  2 " << ytop + 2.5 * d
           << " 150 " << v * v0 << '\n';
    if (step % 2000 == 0) {
      profile << step << " 20 300\n";
      for (int bin = 0; bin < 20; ++bin) {
        const double z = bin - 9.5;  // bin centres from -9.5 d to 9.5 d
        const double uz = z < 0 ? 0.2 * std::exp(z / 2) : 0.2 + 0.5 * (std::pow(10, 1.5) - std::pow(10 - z, 1.5)) / 10;
        profile << "  " << bin + 1 << ' ' << ytop + z * d << " 15 " << uz * v0 << '\n';
      }
    }
  }
  write_file(dir / "flow.time", flow.str());
  write_file(dir / "layers.chunk", layers.str());
  write_file(dir / "profile.chunk", profile.str());
  std::string dump;
  for (long step = 0; step <= steps; step += steps / 4)
    dump += dump_frame(step, 0, 16 * d, 0, 60 * d,
                       {{2 * d, 3 * d, d / 2}, {3 * d - run.overlap * d, 3 * d, d / 2}, {8 * d, 3 * d, d / 2}});
  write_file(dir / "dump.chute", dump);
  write_file(dir / "log.lammps",
             "Loop time of 1 on 1 procs for 10 steps with 3 atoms\n\n100.0% CPU use\nLoop time of " +
                 std::to_string(run.loop_seconds) + " on 1 procs for " + std::to_string(steps) +
                 " steps with 3 atoms\n\n97.5% CPU use with 1 MPI tasks\n");
}

cdref::CompareSettings settings_for(const std::vector<fs::path>& dirs)
{
  cdref::CompareSettings s;
  for (const auto& d : dirs) s.run_dirs.push_back(d.string());
  s.run.spectrum.segment_duration_s = 0.25;
  return s;
}

}  // namespace

TEST(Compare, FindsTheContactPeakTheOverlapsAndTheCost)
{
  auto dir = scratch_dir();
  FakeRun soft;
  FakeRun rigid;
  rigid.code = "lmp_cd";
  rigid.model = "rigid";
  rigid.f_contact.reset();
  rigid.tone_amplitude = 0;
  rigid.overlap = 0;
  rigid.loop_seconds = 400;
  write_fake_run(dir / "soft", soft);
  write_fake_run(dir / "rigid", rigid);
  // The rigid flow's second part (a continuation run) took 200 s for as many steps, at half
  // a core; the first part had a core of its own.
  fs::create_directories(dir / "rigid" / "part2");
  write_file(dir / "rigid" / "part2" / "log.lammps", "Loop time of 200 on 1 procs for 49999 steps with 3 atoms\n");
  write_file(dir / "rigid" / "part2" / "timing.txt", "210 100 5\n");
  write_file(dir / "rigid" / "timing.txt", "410 405 5\n");
  auto comparison = cdref::compare_runs(settings_for({dir / "rigid", dir / "soft"}));
  ASSERT_EQ(comparison.runs.size(), 2u);
  const auto& r = comparison.runs[0];
  const auto& s = comparison.runs[1];
  EXPECT_EQ(r.label, "rigid");
  EXPECT_EQ(s.label, "granular hooke 1e-3");
  EXPECT_TRUE(r.stationary && s.stationary);
  ASSERT_TRUE(s.contact_peak);
  EXPECT_NEAR(s.contact_peak->frequency_hz, 1200, 120) << "within the resonance's half width (Q = 5)";
  EXPECT_GT(*s.contact_excess, 2);
  EXPECT_FALSE(r.contact_peak);
  ASSERT_TRUE(s.overlaps);
  EXPECT_NEAR(s.overlaps->max, 0.003, 1e-9);
  EXPECT_EQ(r.overlaps->contacts, 0);
  EXPECT_NEAR(*s.wall_per_physical_second(), 20.0, 0.01);
  EXPECT_NEAR(*r.wall_per_physical_second(), 300.0, 0.2) << "(400 s + 200 s) for two parts of 1 s";
  EXPECT_NEAR(*r.cpu_per_physical_second(), (400 * 1.0 + 200 * 0.5) / 2, 0.2);
  EXPECT_NEAR(r.analysis.results.find("U")->value, 3.0, 0.05);
  EXPECT_NEAR(comparison.fits.find("contact_peak_ratio_granular hooke 1e-3")->value, 1.2, 0.1);

  auto out = dir / "comparison";
  cdref::write_comparison(comparison, settings_for({}), out.string());
  const auto table = read_file(out / "table.csv");
  EXPECT_NE(table.find("\"granular hooke 1e-3\",lammps-granular,hooke,1,"), std::string::npos) << table;
  EXPECT_TRUE(fs::exists(out / "report.md"));
  EXPECT_TRUE(fs::exists(out / "spectra.csv"));
  EXPECT_TRUE(fs::exists(out / "figures" / "spectra.gp"));
  EXPECT_TRUE(fs::exists(out / "figures" / "peaks_vs_k.gp"));
}

TEST(Compare, PeakShiftWithStiffnessAndNonStationaryRuns)
{
  auto dir = scratch_dir();
  std::vector<fs::path> dirs;
  for (double k : {1e3, 1e4, 1e5}) {
    FakeRun run;
    run.k_reduced = k;
    run.f_contact = 10 * std::sqrt(k);  // 316, 1000, 3162 Hz
    run.tone_hz = std::round(1.1 * *run.f_contact);
    run.duration = 1.0;
    dirs.push_back(dir / ("k" + std::to_string(static_cast<int>(k))));
    write_fake_run(dirs.back(), run);
  }
  FakeRun growing;
  growing.u = 0;  // U(t) replaced below by a steady ramp: never stationary
  dirs.push_back(dir / "growing");
  write_fake_run(dirs.back(), growing);
  {
    std::string text = read_file(dirs.back() / "flow.time");
    std::istringstream in(text);
    std::ostringstream out;
    std::string line;
    long row = 0;
    while (std::getline(in, line)) {
      if (line[0] == '#') {
        out << line << '\n';
        continue;
      }
      std::istringstream fields(line);
      double step, ua, uf, v, phi, h;
      fields >> step >> ua >> uf >> v >> phi >> h;
      out << step << ' ' << ua << ' ' << 0.01 * ++row << ' ' << v << ' ' << phi << ' ' << h << '\n';
    }
    write_file(dirs.back() / "flow.time", out.str());
  }
  auto comparison = cdref::compare_runs(settings_for(dirs));
  const auto* exponent = comparison.fits.find("contact_exponent_lammps-granular_hooke");
  ASSERT_NE(exponent, nullptr);
  EXPECT_NEAR(exponent->value, 0.5, 0.05);
  EXPECT_FALSE(comparison.runs.back().stationary);
  EXPECT_NE(comparison.runs.back().window_note.find("NOT STATIONARY"), std::string::npos);
  EXPECT_NE(comparison.runs.back().label.find("(growing)"), std::string::npos) << "duplicate labels are made unique";
}

TEST(Compare, RefusesAMissingDirectory)
{
  auto dir = scratch_dir();
  EXPECT_THROW(cdref::compare_runs(settings_for({dir / "absent"})), cdpost::InputError);
  EXPECT_THROW(cdref::compare_runs(settings_for({})), cdpost::AnalysisError);
}
