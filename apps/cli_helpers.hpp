#pragma once

/// @file
/// Pieces shared by the long-running commands (run, generalize): a list of orientations from the
/// command line, and a progress bar on stderr.

#include <mutex>
#include <string>
#include <vector>

namespace graspsynth::apps {

/// Parses a comma-separated list of orientations (deg); each item is a number or a range
/// FROM:TO:STEP (inclusive, STEP > 0), e.g. "0:20:1,100:120:5" or "40,45". Throws InputError
/// naming `option` and the item.
std::vector<double> ParseOrientationList(const std::string& text, const std::string& option);

/// A progress bar per named stage on stderr, redrawn in place on a terminal; elsewhere (logs,
/// pipes) a line "NAME: DONE/TOTAL (WHAT)" at every tenth of the stage. Thread-safe.
class ProgressBar {
 public:
  ProgressBar();

  /// Shows `done` of `total` steps of stage `name`, working on `what`. A new name starts a
  /// new bar.
  void Update(const std::string& name, int done, int total, const std::string& what);
  /// Ends the current bar's line.
  void Finish();

 private:
  bool tty_;
  bool started_ = false;
  std::string stage_;
  int last_tenth_ = -1;
  std::mutex mutex_;
};

}  // namespace graspsynth::apps
