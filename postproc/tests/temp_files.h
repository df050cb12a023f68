// Test helpers: a scratch directory per test and writing plain or gzip text files into it.
#pragma once

#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <cstdlib>
#include <string>
#include <vector>
#include <unistd.h>

#include <gtest/gtest.h>

namespace cdpost::testing {

// Removes the scratch directories at exit (keep them with CDPOST_KEEP_TEST_FILES=1).
struct ScratchRegistry {
  std::vector<std::filesystem::path> made;
  ~ScratchRegistry()
  {
    if (std::getenv("CDPOST_KEEP_TEST_FILES")) return;
    std::error_code ignored;
    for (const auto& dir : made) std::filesystem::remove_all(dir, ignored);
  }
};

inline std::filesystem::path scratch_dir()
{
  static ScratchRegistry registry;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::temp_directory_path() /
             ("cdpost-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" + info->name());
  if (std::filesystem::create_directories(dir)) registry.made.push_back(dir);
  return dir;
}

inline std::string write_file(const std::filesystem::path& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

inline std::string write_gzip(const std::filesystem::path& path, const std::string& text)
{
  gzFile file = gzopen(path.c_str(), "wb");
  gzwrite(file, text.data(), static_cast<unsigned>(text.size()));
  gzclose(file);
  return path.string();
}

}  // namespace cdpost::testing
