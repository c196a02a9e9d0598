#pragma once

/// @file
/// Always-on invariant checks (the middle of the three error levels of STYLE.md).
///
/// - Bad user input or files: throw graspsynth::InputError (common/errors.hpp).
/// - Invariants that must hold in every build: GS_DEMAND(condition, message). A failure prints
///   the condition, the message and the source location to stderr and aborts.
/// - Hot-loop debug checks: plain assert().

#include <string_view>

namespace graspsynth::internal {

/// Prints the failed condition with its location and aborts. Never returns.
[[noreturn]] void DemandFailed(std::string_view condition, std::string_view message,
                               std::string_view file, int line);

}  // namespace graspsynth::internal

/// Aborts with a message when `condition` is false, in every build type.
#define GS_DEMAND(condition, message)                                            \
  do {                                                                           \
    if (!(condition)) {                                                          \
      ::graspsynth::internal::DemandFailed(#condition, (message), __FILE__, __LINE__); \
    }                                                                            \
  } while (false)
