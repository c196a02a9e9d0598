#pragma once

/// @file
/// `graspsynth export-mjcf`: the robot, the table and the object at a placement, optionally
/// with a grasp's trajectory as keyframes, written as an MJCF model for MuJoCo (docs/mujoco.md).

namespace CLI {
class App;
}

namespace graspsynth::apps {

/// Registers `graspsynth export-mjcf --out FILE [--trajectory FILE] [--theta DEG] [--at X,Y]
/// [--mujoco-servo stiff|soft] [--time-step S]`.
void AddExportMjcfCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
