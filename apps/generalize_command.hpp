#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth generalize`, the engine of experiments 2 and 3 (generalization,
/// leave-one-out, extrapolation, ablations).
void AddGeneralizeCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
