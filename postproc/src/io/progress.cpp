#include "io/progress.h"

#include <unistd.h>

#include <cstdio>

namespace cdpost {

Progress::Progress(std::string label, bool enabled, bool force)
    : label_(std::move(label)), shown_(enabled && (force || isatty(STDERR_FILENO)))
{
}

Progress::~Progress()
{
  if (printed_) std::fprintf(stderr, "\n");
}

void Progress::update(double fraction, const std::string& detail)
{
  if (!shown_) return;
  auto now = std::chrono::steady_clock::now();
  if (now - start_ < std::chrono::seconds(1)) return;
  if (printed_ && now - last_ < std::chrono::milliseconds(250)) return;
  last_ = now;
  printed_ = true;
  std::fprintf(stderr, "\r%s: %5.1f%% %s", label_.c_str(), 100.0 * fraction, detail.c_str());
  std::fflush(stderr);
}

}  // namespace cdpost
