#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth view`: serves the browser viewer (viewer/viewer_server.hpp) and
/// replays a trajectory file or a demonstration log in it at the file's rate, until the end of
/// the replay (after --hold), Ctrl-C or SIGTERM.
void AddViewCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
