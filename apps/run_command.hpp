#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth run`, the main job of the README.
void AddRunCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
