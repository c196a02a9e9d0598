#pragma once

/// @file
/// The request of `graspsynth ik`: which of the arm's branches to solve for. Its one option is
/// described here (IkOptions) and read by the command; Python's ik takes its branch as an array
/// argument, one per target. `fk` has no option but its input and robot files.

#include <optional>

#include <Eigen/Core>

#include "request/option.hpp"

namespace graspsynth::request {

/// Which IK solutions to print.
struct IkRequest {
  /// The signs (GC2, GC4, GC6) of S2, E1 and W1, each 1 or -1; none: all 8 branches.
  std::optional<Eigen::Vector3i> branch;
};

/// The options of IkRequest.
const OptionList<IkRequest>& IkOptions();

}  // namespace graspsynth::request
