#pragma once

/// @file
/// What the other parts of the module share from the simulation bindings.

#include <cstdint>

#include "simulation/robustness.hpp"
#include "simulation/trial.hpp"

namespace graspsynth::python {

/// The perturbed replays' options of the Python functions: `trials` replays from `seed` on
/// `threads` workers, the physics perturbation on or off, the motion noise scaled by
/// `noise_scale`. Throws InputError naming the invalid value.
RobustnessOptions RobustnessOptionsOf(int trials, uint64_t seed, int threads, bool physics,
                                      double noise_scale, const TrialOptions& trial);

}  // namespace graspsynth::python
