#pragma once

/// @file
/// Wall time for the figures the tools report (stage times, trial speeds, tick budgets): one
/// monotonic clock, in seconds.

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

}  // namespace graspsynth
