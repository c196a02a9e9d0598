#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth fk` and `graspsynth ik` on `app`. A command that met malformed input
/// lines sets *exit_code to 1 (it still processes every line).
void AddKinematicsCommands(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
