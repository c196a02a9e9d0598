#pragma once

/// @file
/// Shared inputs of the synthesis tests: the shipped model and scripted-grasp libraries, built
/// once per test binary.

#include "solver/synthesis.hpp"
#include "tests/utils/scripted_library.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth::testing {

/// Scripted grasps at 40, 60 and 80 deg, wrist right of the handle.
inline const GraspLibrary& Library406080() {
  static const GraspLibrary library = ScriptedLibrary(
      ShippedSimulationModel().robot(), ShippedSimulationModel().scene(), {40.0, 60.0, 80.0});
  return library;
}

/// The hard case: 30 and 40 deg with the wrist left of the handle, 50 and 60 deg right of it.
inline const GraspLibrary& SideSwitchLibrary() {
  static const GraspLibrary library = [] {
    const RobotModel& robot = ShippedSimulationModel().robot();
    const SceneModel& scene = ShippedSimulationModel().scene();
    GraspLibrary l;
    l.entries.push_back(ScriptedEntry(robot, scene, 30.0, -1));
    l.entries.push_back(ScriptedEntry(robot, scene, 40.0, -1));
    l.entries.push_back(ScriptedEntry(robot, scene, 50.0, +1));
    l.entries.push_back(ScriptedEntry(robot, scene, 60.0, +1));
    return l;
  }();
  return library;
}

/// A synthesis model over Library406080.
inline const SynthesisModel& Model406080() {
  static const SynthesisModel model(ShippedSimulationModel().robot(),
                                    ShippedSimulationModel().scene(), Library406080());
  return model;
}

inline const SynthesisModel& SideSwitchModel() {
  static const SynthesisModel model(ShippedSimulationModel().robot(),
                                    ShippedSimulationModel().scene(), SideSwitchLibrary());
  return model;
}

}  // namespace graspsynth::testing
