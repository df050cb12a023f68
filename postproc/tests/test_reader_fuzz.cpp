// Randomised robustness test of the file readers: mutated files must either read or fail
// with one InputError line that starts with the file name and holds no control byte (a binary
// byte is never echoed); never crash or read non-finite values.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io/ave_chunk.h"
#include "io/ave_time.h"
#include "io/dump.h"
#include "lammps_text.h"
#include "temp_files.h"

namespace cdpost {
namespace {

std::string mutate(std::string text, std::mt19937& rng)
{
  const std::string alphabet = "0123456789 .-+eE#\nITEMnaXx\t";
  std::uniform_int_distribution<int> kind(0, 6);
  int edits = 1 + static_cast<int>(rng() % 3);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    size_t at = rng() % text.size();
    switch (kind(rng)) {
      case 0: text.erase(at, 1); break;
      case 1: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
      case 2: text[at] = alphabet[rng() % alphabet.size()]; break;
      case 3: text.resize(at); break;
      case 4: text.erase(at, rng() % 40); break;
      case 5: text.insert(at, 1, static_cast<char>(rng() % 256)); break;  // any byte: NULs, control bytes
      default: text.insert(at, text.substr(at, rng() % 60)); break;
    }
  }
  return text;
}

void expect_all_finite(const std::vector<double>& values)
{
  for (double v : values) ASSERT_TRUE(std::isfinite(v));
}

void read_whole(const std::string& kind, const std::string& path)
{
  if (kind == "time") {
    for (const auto& column : read_ave_time(path).columns) expect_all_finite(column);
  } else if (kind == "chunk") {
    expect_all_finite(read_ave_chunk(path).values);
  } else {
    DumpReader reader(path);
    DumpFrame frame;
    while (reader.next(frame)) {
      expect_all_finite(frame.values);
      ASSERT_EQ(frame.values.size(), frame.atoms * frame.columns.size());
    }
  }
}

std::string valid_text(const std::string& kind)
{
  if (kind == "time")
    return testing::ave_time_text({"TimeStep", "v_u", "v_v"}, {{1, 0.5, 2}, {2, 0.25, -1}, {3, 1e-3, 4}});
  if (kind == "chunk")
    return testing::ave_chunk_text({"Coord1", "vx"}, {10, 20, 30}, 3,
                                   [](size_t b, size_t c, size_t) { return 0.1 * b + c; });
  return testing::dump_frame_text(5, 4, 4, {{1, 1, 1, 0.5, 0, 0.25}, {2, 2, 2, 0.1, 0.2, 0.25}}) +
         testing::dump_frame_text(6, 4, 4, {{1, 1, 1, 0.5, 0, 0.25}, {2, 2, 2, 0.1, 0.2, 0.25}});
}

TEST(ReaderFuzz, MutatedFilesReadOrFailWithOneLocatedLine)
{
  auto dir = testing::scratch_dir();
  std::mt19937 rng(20240611);
  int failures = 0, successes = 0;
  for (const std::string kind : {"time", "chunk", "dump"}) {
    for (int trial = 0; trial < 400; ++trial) {
      auto text = mutate(valid_text(kind), rng);
      auto path = (dir / (kind + std::to_string(trial))).string();
      if (trial % 4 == 0) testing::write_gzip(path, text);
      else testing::write_file(path, text);
      try {
        read_whole(kind, path);
        ++successes;
      } catch (const InputError& e) {
        std::string message = e.what();
        EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (char c : message) EXPECT_FALSE((c >= 0 && c < 0x20 && c != '\t') || c == 0x7f) << message;
        ++failures;
      }
    }
  }
  EXPECT_GT(failures, 100);
  EXPECT_GT(successes, 10);
}

}  // namespace
}  // namespace cdpost
