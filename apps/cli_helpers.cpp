#include "apps/cli_helpers.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "common/errors.hpp"

namespace graspsynth::apps {
namespace {

// The number in `item`, or nullopt-like NaN when it is not a finite number.
double Number(const std::string& item) {
  char* end = nullptr;
  const double v = std::strtod(item.c_str(), &end);
  if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v)) return NAN;
  return v;
}

}  // namespace

std::vector<double> ParseOrientationList(const std::string& text, const std::string& option) {
  std::vector<double> thetas;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto bad = [&](const std::string& why) {
      return InputError(option + ": '" + item + "' " + why + " (in '" + text + "')");
    };
    std::vector<std::string> parts;
    std::stringstream is(item);
    std::string part;
    while (std::getline(is, part, ':')) parts.push_back(part);
    if (parts.size() == 1) {
      const double v = Number(parts[0]);
      if (std::isnan(v)) throw bad("is not a finite number of degrees");
      thetas.push_back(v);
    } else if (parts.size() == 3) {
      const double from = Number(parts[0]), to = Number(parts[1]), step = Number(parts[2]);
      if (std::isnan(from) || std::isnan(to) || std::isnan(step)) {
        throw bad("is not a range FROM:TO:STEP of finite numbers");
      }
      if (!(step > 0.0) || to < from) throw bad("needs FROM <= TO and STEP > 0");
      const int n = static_cast<int>(std::floor((to - from) / step + 1e-9));
      if (n > 100000) throw bad("has more than 100000 orientations");
      for (int k = 0; k <= n; ++k) thetas.push_back(from + k * step);
    } else {
      throw bad("is neither a number nor a range FROM:TO:STEP");
    }
  }
  if (thetas.empty()) throw InputError(option + ": no orientation in '" + text + "'");
  return thetas;
}

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
