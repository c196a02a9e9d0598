#pragma once

/// @file
/// The request of `graspsynth demos generate` and `demos calibrate`: the synthetic operator's
/// trials, with the operator file's seed, trial counts and object positions overridden. Its
/// options are described once (DemosGenerateOptions, DemosCalibrateOptions share the seed, the
/// trial count and the threads) and applied to the operator's options once
/// (ApplyToOperator). The operator file (--operator), robot, scene, object and output are not
/// options. Python has no counterpart.

#include <cstdint>
#include <optional>
#include <string>

#include "learning_data/operator_options.hpp"
#include "request/option.hpp"

namespace graspsynth::request {

/// What to generate or calibrate; unset options keep the operator file's.
struct DemosRequest {
  std::optional<uint64_t> seed;               ///< none: the operator file's
  std::optional<int> trials_per_orientation;  ///< the same count everywhere; none: the file's
  int threads = 0;                            ///< 0: all cores; changes no result
  std::string x, y;      ///< generate: a grid of object positions, m (both or neither)
  int iterations = 3;    ///< calibrate: generate-and-correct rounds
  double damping = 0.7;  ///< calibrate: fraction of the difference corrected per round
};

/// The options of `demos generate` and of `demos calibrate`, in the order the flags list them.
const OptionList<DemosRequest>& DemosGenerateOptions();
const OptionList<DemosRequest>& DemosCalibrateOptions();

/// `options` (an operator file's) with the seed, the trial count and the object positions of
/// `request` over them. Throws InputError, naming the option, for x without y or positions the
/// operator cannot use.
OperatorOptions ApplyToOperator(const DemosRequest& request, OperatorOptions options);

}  // namespace graspsynth::request
