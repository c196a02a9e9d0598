#pragma once

/// @file
/// Wall time for the figures the tools report (stage times, trial speeds, tick budgets): one
/// monotonic clock, in seconds; and the CPU time of the calling thread (a trial's cost).

#include <time.h>

#include <chrono>

namespace graspsynth {

/// The monotonic clock every wall time is measured with.
using WallClock = std::chrono::steady_clock;

/// Seconds from `start` to `end` on WallClock.
inline double SecondsBetween(WallClock::time_point start, WallClock::time_point end) {
  return std::chrono::duration<double>(end - start).count();
}

/// Seconds elapsed since `start` on WallClock.
inline double SecondsSince(WallClock::time_point start) {
  return std::chrono::duration<double>(WallClock::now() - start).count();
}

/// CPU seconds the calling thread has used (CLOCK_THREAD_CPUTIME_ID).
inline double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace graspsynth
