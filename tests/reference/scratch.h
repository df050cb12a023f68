// Test helpers: one scratch directory per test (kept with CDREF_KEEP_TEST_FILES=1), writing
// text files, and the LAMMPS output formats the reference decks produce.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace cdref::testing {

struct ScratchRegistry {
  std::vector<std::filesystem::path> made;
  ~ScratchRegistry()
  {
    if (std::getenv("CDREF_KEEP_TEST_FILES")) return;
    std::error_code ignored;
    for (const auto& dir : made) std::filesystem::remove_all(dir, ignored);
  }
};

inline std::filesystem::path scratch_dir(const std::string& name = "")
{
  static ScratchRegistry registry;
  std::string stem = name;
  if (stem.empty()) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    stem = std::string(info->test_suite_name()) + "-" + info->name();
  }
  auto dir = std::filesystem::temp_directory_path() / ("cdref-" + std::to_string(::getpid()) + "-" + stem);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  registry.made.push_back(dir);
  return dir;
}

inline std::string write_file(const std::filesystem::path& path, const std::string& text)
{
  std::ofstream(path) << text;
  return path.string();
}

inline std::string read_file(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A LAMMPS `dump custom ... id type x y vx vy radius` frame of disks {x, y, r}.
struct DumpDisk {
  double x, y, r;
};
inline std::string dump_frame(long step, double xlo, double xhi, double ylo, double yhi,
                              const std::vector<DumpDisk>& disks)
{
  std::ostringstream out;
  out.precision(17);
  out << "ITEM: TIMESTEP\n"
      << step << "\nITEM: NUMBER OF ATOMS\n"
      << disks.size() << "\nITEM: BOX BOUNDS pp ff pp\n"
      << xlo << ' ' << xhi << '\n'
      << ylo << ' ' << yhi << "\n-0.0003 0.0003\nITEM: ATOMS id type x y vx vy radius\n";
  for (size_t i = 0; i < disks.size(); ++i)
    out << i + 1 << " 1 " << disks[i].x << ' ' << disks[i].y << " 0 0 " << disks[i].r << '\n';
  return out.str();
}

}  // namespace cdref::testing
