#include <gtest/gtest.h>

#include "io/ave_chunk.h"
#include "io/ave_time.h"
#include "io/chute_record.h"
#include "io/dump.h"
#include "lammps_text.h"
#include "temp_files.h"

namespace cdpost {
namespace {

using testing::scratch_dir;
using testing::write_file;
using testing::write_gzip;

// The error raised by `action`, or "" if none.
template <class Action>
std::string error_of(Action action)
{
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AveTime, ReadsNamedColumns)
{
  auto path = write_file(scratch_dir() / "flow.time",
                         testing::ave_time_text({"TimeStep", "v_u", "v_v"}, {{100, 1.5, -2}, {200, 1.25, 3e-5}}));
  auto table = read_ave_time(path);
  ASSERT_EQ(table.rows(), 2u);
  EXPECT_DOUBLE_EQ(table.column("v_u")[1], 1.25);
  EXPECT_DOUBLE_EQ(table.column("v_v")[1], 3e-5);
  EXPECT_EQ(table.row_lines[0], 3);
}

TEST(AveTime, ReadsGzip)
{
  auto path = write_gzip(scratch_dir() / "flow.time.gz", testing::ave_time_text({"TimeStep", "v_u"}, {{1, 2}, {2, 3}}));
  EXPECT_DOUBLE_EQ(read_ave_time(path).column("v_u")[1], 3);
}

TEST(AveTime, AcceptsRepeatedHeaderAfterRestart)
{
  std::string text = testing::ave_time_text({"TimeStep", "v_u"}, {{1, 2}, {2, 3}});
  text += "# TimeStep v_u\n3 4\n";
  EXPECT_EQ(read_ave_time(write_file(scratch_dir() / "f", text)).rows(), 3u);
}

TEST(AveTime, ErrorsNameFileLineAndProblem)
{
  auto dir = scratch_dir();
  EXPECT_EQ(error_of([&] { read_ave_time(write_file(dir / "empty", "")); }),
            (dir / "empty").string() + ": file is empty");
  EXPECT_EQ(error_of([&] { read_ave_time(write_file(dir / "short", "# TimeStep v_u\n1 2\n2\n")); }),
            (dir / "short").string() + ":3: expected 2 values (TimeStep, v_u), found 1");
  EXPECT_EQ(error_of([&] { read_ave_time(write_file(dir / "bad", "# TimeStep v_u\n1 2x\n")); }),
            (dir / "bad").string() + ":2: bad number '2x' for column v_u");
  EXPECT_EQ(error_of([&] { read_ave_time(write_file(dir / "nan", "# TimeStep v_u\n1 nan\n")); }),
            (dir / "nan").string() + ":2: non-finite value 'nan' for column v_u");
  EXPECT_EQ(error_of([&] { read_ave_time(write_file(dir / "nohead", "1 2\n")); }),
            (dir / "nohead").string() + ":1: data before any '#' header line naming the columns");
  EXPECT_EQ(error_of([&] { read_ave_time(write_file(dir / "back", "# TimeStep v_u\n2 1\n1 1\n")); }),
            (dir / "back").string() + ":3: TimeStep 1 does not increase (overlapping restart output?)");
  EXPECT_EQ(error_of([&] { read_ave_time((dir / "missing").string()); }),
            (dir / "missing").string() + ": cannot open (no such file)");
}

TEST(AveTime, MissingColumnListsTheAvailableOnes)
{
  auto table = read_ave_time(write_file(scratch_dir() / "f", "# TimeStep v_u\n1 2\n"));
  EXPECT_NE(error_of([&] { table.column("v_x"); }).find("no column 'v_x' (columns: TimeStep, v_u)"), std::string::npos);
}

TEST(AveTime, TruncatedGzipIsAnError)
{
  auto dir = scratch_dir();
  std::string text;
  for (int i = 1; i < 5000; ++i) text += std::to_string(i) + " " + std::to_string(i * 0.37) + "\n";
  auto path = write_gzip(dir / "full.gz", "# TimeStep v_u\n" + text);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  auto cut = write_file(dir / "cut.gz", bytes.substr(0, bytes.size() / 2));
  EXPECT_NE(error_of([&] { read_ave_time(cut); }).find("corrupt or truncated compressed data"), std::string::npos);
}

std::string chunk_text(size_t blocks)
{
  std::vector<long> steps;
  for (size_t b = 0; b < blocks; ++b) steps.push_back(1000 * static_cast<long>(b + 1));
  return testing::ave_chunk_text({"Coord1", "Ncount", "vx"}, steps, 3,
                                 [](size_t b, size_t c, size_t k) { return k == 0 ? c + 0.5 : 10.0 * b + c + k; });
}

TEST(AveChunk, ReadsBlocks)
{
  auto series = read_ave_chunk(write_file(scratch_dir() / "p.chunk", chunk_text(2)));
  ASSERT_EQ(series.blocks(), 2u);
  EXPECT_EQ(series.chunks, 3u);
  EXPECT_EQ(series.names, (std::vector<std::string>{"Coord1", "Ncount", "vx"}));
  EXPECT_DOUBLE_EQ(series.timesteps[1], 2000);
  EXPECT_DOUBLE_EQ(series.value(1, 2, series.column_index("vx")), 14);
  EXPECT_DOUBLE_EQ(series.value(0, 1, series.column_index("Coord1")), 1.5);
}

TEST(AveChunk, TruncatedBlockNamesTheLine)
{
  auto dir = scratch_dir();
  std::string text = chunk_text(2);
  text = text.substr(0, text.rfind("  3"));  // drop the last chunk row
  auto path = write_file(dir / "p.chunk", text);
  EXPECT_EQ(error_of([&] { read_ave_chunk(path); }),
            path + ":10: file ends inside the block of timestep 2000 (2 of 3 chunk rows)");
}

TEST(AveChunk, ChangingChunkCountIsAnError)
{
  std::string text = chunk_text(1) + "2000 4 100\n";
  auto path = write_file(scratch_dir() / "p.chunk", text);
  EXPECT_EQ(error_of([&] { read_ave_chunk(path); }),
            path + ":8: number of chunks changed from 3 to 4 (fix the bin bounds in the deck)");
}

TEST(AveChunk, HeaderWithoutChunkLineIsAnError)
{
  auto path = write_file(scratch_dir() / "p.chunk", "# Timestep Number-of-chunks Total-count\n100 1 1\n");
  EXPECT_EQ(error_of([&] { read_ave_chunk(path); }), path + ":2: no '# Chunk ...' header line naming the columns");
}

std::string two_frames()
{
  return testing::dump_frame_text(0, 10, 5, {{1, 1, 1, 0.5, 0, 0.25}, {2, 3, 1, 1.5, 0.1, 0.25}}) +
         testing::dump_frame_text(100, 10, 5, {{1, 1.1, 1, 0.6, 0, 0.25}, {2, 3.2, 1, 1.7, 0.1, 0.25}});
}

TEST(Dump, StreamsFramesPlainAndGzip)
{
  auto dir = scratch_dir();
  for (const auto& path : {write_file(dir / "d.txt", two_frames()), write_gzip(dir / "d.gz", two_frames())}) {
    DumpReader reader(path);
    DumpFrame frame;
    ASSERT_TRUE(reader.next(frame));
    EXPECT_EQ(frame.timestep, 0);
    ASSERT_TRUE(reader.next(frame));
    EXPECT_EQ(frame.timestep, 100);
    EXPECT_EQ(frame.atoms, 2u);
    EXPECT_DOUBLE_EQ(frame.xhi, 10);
    EXPECT_DOUBLE_EQ(frame.value(1, frame.column_index("vx")), 1.7);
    EXPECT_FALSE(reader.next(frame));
  }
}

TEST(Dump, TruncatedFrameNamesTheLine)
{
  std::string text = two_frames();
  text = text.substr(0, text.rfind("2 1 3.2"));
  auto path = write_file(scratch_dir() / "d.txt", text);
  DumpReader reader(path);
  DumpFrame frame;
  reader.next(frame);
  EXPECT_EQ(error_of([&] { reader.next(frame); }),
            path + ":21: file ends where atom 2 of 2 was expected (truncated dump?)");
}

// Bytes no text file holds: a NUL at `nul_at` among bytes of every value (LAMMPS's binary dump
// writes doubles and ints: NULs and control bytes throughout).
std::string binary_bytes(size_t size, size_t nul_at)
{
  std::string bytes;
  for (size_t i = 0; i < size; ++i) bytes.push_back(static_cast<char>((i * 37 + 11) % 256));
  bytes[nul_at] = '\0';
  return bytes;
}

// The message names the file and says binary; it is one short line of printable characters.
void expect_binary_refused(const std::string& message, const std::string& path, long line)
{
  EXPECT_EQ(message.rfind(path + ":" + std::to_string(line) + ": binary data, not text", 0), 0u) << message;
  EXPECT_LT(message.size(), path.size() + 200);
  for (char c : message) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "byte " << int(static_cast<unsigned char>(c));
}

TEST(Dump, BinaryFilesAreRefusedWithoutEchoingTheirBytes)
{
  auto dir = scratch_dir();
  const std::string bytes = binary_bytes(15000, 9);
  const std::string after_text = testing::dump_frame_text(0, 10, 5, {{1, 1, 1, 0.5, 0, 0.25}});
  const struct {
    std::string path;
    long line;
  } cases[] = {
      {write_file(dir / "dump.bin", bytes), 1},                                                 // a binary dump
      {write_gzip(dir / "dump.bin.gz", bytes), 1},                                              // gzip, but not of text
      {write_file(dir / "nul.txt", after_text + "1 1 2" + std::string(1, '\0') + " 3\n"), 11},  // a NUL in a line
      {write_file(dir / "ctrl.txt", after_text + "\x01\x02\n"), 11},                            // control bytes
  };
  for (const auto& c : cases) {
    const auto message = error_of([&] {
      DumpReader reader(c.path);
      DumpFrame frame;
      while (reader.next(frame)) {
      }
    });
    expect_binary_refused(message, c.path, c.line);
  }
  // The other readers share the line source.
  const auto path = write_file(dir / "flow.time", bytes);
  expect_binary_refused(error_of([&] { read_ave_time(path); }), path, 1);
}

TEST(Dump, BoxBoundsFlagsGiveThePeriodicity)
{
  auto dir = scratch_dir();
  const std::vector<testing::DumpAtom> one = {{1, 1, 1, 0, 0, 0.25}};
  auto periodic_of = [&](const std::string& flags) {
    DumpReader reader(write_file(dir / "d.txt", testing::dump_frame_text(0, 10, 5, one, flags)));
    DumpFrame frame;
    reader.next(frame);
    return frame.periodic;
  };
  EXPECT_EQ(periodic_of("pp fm pp"), (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(periodic_of("ff ff pp"), (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(periodic_of("xy xz yz pp ss pp"), (std::array<bool, 3>{true, false, true}));  // triclinic
  EXPECT_FALSE(periodic_of(""));
  const auto path = write_file(dir / "bad.txt", testing::dump_frame_text(0, 10, 5, one, "pp q"));
  EXPECT_EQ(error_of([&] {
              DumpReader reader(path);
              DumpFrame frame;
              reader.next(frame);
            }),
            path + ":5: expected three boundary flags (e.g. 'pp fm pp') after 'ITEM: BOX BOUNDS', found ' pp q'");
}

// A triclinic box's bounds are those of its tilted cell (xlo + min(0, xy) ...): the frame keeps
// the cell's own and its tilt.
TEST(Dump, TriclinicBoundsGiveTheCellAndItsTilt)
{
  const auto path = write_file(scratch_dir() / "tilted.txt",
                               "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n"
                               "-1.5 10 -1.5\n0 5 0\n-0.5 0.5 0\nITEM: ATOMS id x y\n1 2 3\n");
  DumpReader reader(path);
  DumpFrame frame;
  ASSERT_TRUE(reader.next(frame));
  EXPECT_DOUBLE_EQ(frame.xy, -1.5);
  EXPECT_DOUBLE_EQ(frame.xlo, 0.0);
  EXPECT_DOUBLE_EQ(frame.xhi, 10.0);
  EXPECT_DOUBLE_EQ(frame.yhi - frame.ylo, 5.0);
}

// chute.params as inputs/in.chute prints it: '#' comments, "name value" lines.
TEST(ChuteRecord, ReadsNamedValuesAndRefusesMalformedLines)
{
  const auto dir = scratch_dir();
  EXPECT_FALSE(read_chute_record(dir.string()));
  const auto path = write_file(dir / "chute.params", "# in.chute\ny_top_m 0.015\nsample_rate_hz 1000\n\nd_m 5.0e-4\n");
  auto record = read_chute_record(dir.string());
  ASSERT_TRUE(record);
  EXPECT_EQ(record->source, path);
  EXPECT_DOUBLE_EQ(*record->find("y_top_m"), 0.015);
  EXPECT_DOUBLE_EQ(*record->find("d_m"), 5e-4);
  EXPECT_FALSE(record->find("g_mps2"));
  write_file(dir / "chute.params", "y_top_m 0.015\ny_top_m 0.02\n");
  EXPECT_EQ(error_of([&] { read_chute_record(dir.string()); }), path + ":2: 'y_top_m' is given twice");
  write_file(dir / "chute.params", "y_top_m\n");
  EXPECT_EQ(error_of([&] { read_chute_record(dir.string()); }),
            path + ":1: expected a name and a value, found 1 fields");
  write_file(dir / "chute.params", "d_m nan\n");
  EXPECT_EQ(error_of([&] { read_chute_record(dir.string()); }), path + ":1: non-finite value 'nan' for d_m");
}

}  // namespace
}  // namespace cdpost
