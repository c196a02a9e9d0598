#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth demos generate` (the synthetic operator: physics-labelled
/// demonstration logs) and `graspsynth demos calibrate` (fits the operator's intended grasp
/// positions so that its successful trials reproduce the paper's Table I).
void AddDemosCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
