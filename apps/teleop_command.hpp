#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth teleop`: the live teleoperation server (teleop/teleop_session.hpp over
/// teleop/udp_link.hpp at the control rate, with the browser viewer when asked), and
/// `graspsynth teleop-client`: replays a demonstration log over UDP as a tracker and a glove
/// would, and `graspsynth teleop-keygen`: writes a shared key for the link.
void AddTeleopCommands(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
