#include "apps/cli_helpers.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace graspsynth::apps {

ProgressBar::ProgressBar() : tty_(::isatty(STDERR_FILENO) != 0) {}

void ProgressBar::Update(const std::string& name, int done, int total, const std::string& what) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (total <= 0) return;
  if (!started_ || name != stage_) {
    if (tty_ && started_) std::fprintf(stderr, "\n");
    stage_ = name;
    last_tenth_ = -1;
    started_ = true;
  }
  const int width = 30;
  const int filled = std::min(done, total) * width / total;
  if (tty_) {
    std::fprintf(stderr, "\r%-9s [%s%s] %d/%d  %-36.36s", name.c_str(),
                 std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(), done,
                 total, what.c_str());
  } else if (done * 10 / total != last_tenth_) {
    last_tenth_ = done * 10 / total;
    if (what.empty()) {
      std::fprintf(stderr, "%s: %d/%d\n", name.c_str(), done, total);
    } else {
      std::fprintf(stderr, "%s: %d/%d (%s)\n", name.c_str(), done, total, what.c_str());
    }
  }
  std::fflush(stderr);
}

void ProgressBar::Finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (tty_ && started_) std::fprintf(stderr, "\n");
  started_ = false;
}

}  // namespace graspsynth::apps
