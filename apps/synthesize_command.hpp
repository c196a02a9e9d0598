#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth synthesize --library FILE --theta DEG [--method interp|line|nearest]
/// [--no-refine] [--start q1,...,q7] [--seed S] [--perturb N] [--force] --out grasp.json`:
/// a grasp for an object orientation from the grasp library (solver/synthesis.hpp), checked by
/// the physics gate (gate/physics_gate.hpp) and written as a graspsynth-grasp/1 file
/// (gate/grasp_file.hpp). Bad queries (theta outside the range with interp, a start outside
/// the joint limits or in collision, a library of another version or corrupt) throw InputError
/// (exit status 2, nothing written); a grasp that cannot be played or fails the gate sets
/// *exit_code to 1 and writes nothing unless --force, which writes the failed validation.
void AddSynthesizeCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
