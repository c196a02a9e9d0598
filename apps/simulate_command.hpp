#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth simulate TRAJECTORY.json --out report.json [--perturb N] ...`: the
/// nominal grasp-and-lift trial of a joint trajectory in the ODE world and, with --perturb, its
/// robustness under time scaling and waypoint noise. Sets *exit_code to 1 when the nominal
/// trial fails (the report is written all the same).
///
/// Also registers `graspsynth scripted-grasp --theta DEG --out FILE`: writes the scripted
/// (hand-made) grasp trajectory of motion/scripted_grasp.hpp; examples/grasp_60deg.json is
/// its output for 60 deg.
void AddSimulateCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
