#pragma once

/// @file
/// The paper's Fig. 8 (mean pre-grasp and grasp wrist positions per orientation, the wrist
/// line, the grasp region and the object outline, object-centred top view) drawn by gnuplot as
/// SVG. Used by `graspsynth analyze --plot` and `graspsynth run`.

#include <filesystem>
#include <string>

#include "analysis/analysis_report.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::apps {

/// Draws Fig. 8 of `analysis` (object outline from `scene`) with the program `gnuplot` and
/// writes the SVG to `svg_path` atomically. Throws InputError when gnuplot cannot be started or
/// fails (with its output) or the temporary folder cannot be made.
void DrawFigure8(const DemonstrationAnalysis& analysis, const SceneModel& scene,
                 const std::string& gnuplot, const std::filesystem::path& svg_path);

}  // namespace graspsynth::apps
