#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth select DIR --out library.json [--perturb N] [--seed S] [--threads T]`:
/// the robustness score of every successful demonstration of a folder of logs and the most
/// robust one per orientation (learning_data/representative_selection.hpp), written as a
/// graspsynth-library/1 file. Sets *exit_code to 1 when no orientation could be selected (the
/// library is written all the same).
void AddSelectCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
