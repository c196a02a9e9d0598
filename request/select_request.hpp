#pragma once

/// @file
/// The request of `graspsynth select` and of Python's select_representatives: the robustness
/// score of every successful demonstration of a folder and the most robust one per orientation
/// (learning_data/representative_selection.hpp). Its options are described once
/// (SelectOptions) and turned into the selection's options once (ToSelectionOptions), for both
/// front ends. The folder, the robot, scene and object are not options, nor are the command's
/// output file and resume.

#include "learning_data/representative_selection.hpp"
#include "request/option.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::request {

/// How to select; the defaults are the library's (SelectionOptions).
struct SelectRequest {
  /// The selection's options the front ends set (replays, seed, threads, early stop,
  /// physics); the rest keep the library's defaults.
  SelectionOptions selection;
};

/// The options of SelectRequest, in the order the front ends list them.
const OptionList<SelectRequest>& SelectOptions();

/// The selection's options of `request` (without a job runner) in `scene` (its grasp region).
/// Throws InputError for options the selection refuses.
SelectionOptions ToSelectionOptions(const SelectRequest& request, const SceneModel& scene);

}  // namespace graspsynth::request
