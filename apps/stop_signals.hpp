#pragma once

/// @file
/// SIGINT / SIGTERM handling for the long-running commands (`view`, `teleop`): while a
/// StopSignals lives, those signals only set a flag that the command's loop polls, so that it
/// can finish its work and write its files; the previous handlers come back when it is
/// destroyed. One at a time per process.

#include <signal.h>

#include <csignal>

namespace graspsynth::apps {

class StopSignals {
 public:
  StopSignals() {
    Flag() = 0;
    struct sigaction action {};
    action.sa_handler = [](int signal) { Flag() = signal; };
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~StopSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// True once SIGINT or SIGTERM arrived.
  bool stopped() const { return Flag() != 0; }
  /// The signal that arrived (0: none).
  int signal() const { return Flag(); }

 private:
  static volatile std::sig_atomic_t& Flag() {
    static volatile std::sig_atomic_t flag = 0;
    return flag;
  }
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace graspsynth::apps
