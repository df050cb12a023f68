// Progress of a long read, shown on stderr (only when stderr is a terminal or when forced).
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
  std::chrono::steady_clock::time_point last_;
};

}  // namespace cdpost
