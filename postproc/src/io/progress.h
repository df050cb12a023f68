// Progress of a long task, shown on stderr (only when stderr is a terminal or when forced,
// and only once the task has run for a second, so short reads stay quiet).
#pragma once

#include <chrono>
#include <string>

namespace cdpost {

class Progress {
 public:
  // `enabled`: show progress at all; it is also off when stderr is not a terminal, unless
  // `force` is set (cdpost --progress).
  Progress(std::string label, bool enabled, bool force = false);
  ~Progress();
  void update(double fraction, const std::string& detail = "");

 private:
  std::string label_;
  bool shown_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_;
};

}  // namespace cdpost
