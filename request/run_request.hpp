#pragma once

/// @file
/// The request of `graspsynth run` and of Python's run: the end-to-end study (Table I, the
/// representative selection, and a grasp for every orientation by each method, validated in
/// physics). Its options are described once (RunOptions) and turned into the study's options
/// once (ToStudyOptions), for both front ends. The demonstrations' folder, the robot, scene and
/// object are not options (the command takes files, Python takes objects), nor are the
/// command's output folder, gnuplot and resume.

#include <cstdint>
#include <filesystem>
#include <string>

#include <optional>
#include <string>

#include "request/option.hpp"
#include "scene/scene_model.hpp"
#include "studies/study.hpp"

namespace graspsynth::request {

/// How to run the study; the defaults are the command's and Python's.
struct RunRequest {
  uint64_t seed = StudyOptions{}.seed;   ///< seed of the whole study
  int threads = StudyOptions{}.threads;  ///< 0: all cores; changes no result
  bool quick = false;                    ///< the reduced study (StudyOptions::UseQuickStudy)
  // none: the study's default, or --quick's.
  std::optional<int> perturb;         ///< gate replays per grasp
  std::optional<int> select_perturb;  ///< selection replays per demonstration
  std::optional<int> sensitivity;     ///< sensitivity replays per factor end
  /// Orientations, deg: numbers and ranges FROM:TO:STEP, comma-separated.
  std::optional<std::string> orientations;
  bool physics_fallback = StudyOptions{}.physics_fallback;
  bool all_replays = !StudyOptions{}.selection_early_stop;
  PhysicsPerturbationOptions physics = StudyOptions{}.perturbation.physics;
  MujocoGateOptions mujoco;  ///< the gate's engines: ode, or ode and MuJoCo's sweep
  HoldMarginOptions hold_margin = StudyOptions{}.hold_margin;  ///< the gates' hold margin
};

/// The options of RunRequest, in the order the front ends list them.
const OptionList<RunRequest>& RunOptions();

/// The study's options of `request` (without a job runner) for the demonstrations of `demos`
/// (empty: the shipped ones of the scene's object) in `scene` (its grasp region, its object).
/// Throws InputError, naming the option, for options the study refuses (an orientation given
/// twice) and for a `demos` that is not a folder.
StudyOptions ToStudyOptions(const RunRequest& request, const SceneModel& scene,
                            const std::filesystem::path& demos = {});

}  // namespace graspsynth::request
