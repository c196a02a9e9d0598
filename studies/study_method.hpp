#pragma once

/// @file
/// The synthesis methods of the study and of `generalize` (experiments/ablations.sh): a label
/// such as "interp+refine/arc" names which stages of the synthesis pipeline (synthesis.hpp)
/// run and with which options.

#include <string>

#include "solver/synthesis.hpp"

namespace graspsynth {

/// One synthesis method of the study: how the grasping motion is made, with or without the
/// refinement, and the variants the ablations turn (experiments/ablations.sh).
struct StudyMethod {
  SynthesisMethod method = SynthesisMethod::kInterp;
  bool refine = true;
  bool ceres = true;  ///< the refinement's stage 1 (with refine)
  bool nlopt = true;  ///< the refinement's stage 2 (with refine)
  ResampleMode resample = ResampleMode::kNormalizedTime;  ///< of the blend
  ReachMethod reach = ReachMethod::kAuto;
  bool thresholds_from_sources = true;  ///< the thresholds stage runs (false: "/strict")
  bool grip_slide = false;              ///< the grip slide runs ("/slide", with a refinement)

  /// The name: the method ("interp", "line", "nearest"), then "+refine" when both refinement
  /// stages run, "+ceres" or "+nlopt" when only that one does, then "/arc" for arc-length
  /// resampling, "/spline" or "/joint" for a reach other than auto, "/strict" for the
  /// refinement's default thresholds whatever the sources did, and "/slide" for the grip slide
  /// (only with a refinement, whose constraints it keeps). E.g. "interp+refine", "line",
  /// "interp+ceres/arc".
  std::string Label() const;
  /// The synthesis pipeline of this method (SynthesisOptions), one part per stage: the method
  /// is the generation stage's (GenerateGraspingMotion), "/arc" its blend's resampling;
  /// "+refine" the refinement stages Ceres then NLopt, "+ceres" and "+nlopt" that one stage
  /// alone, none of them no refinement stage; "/strict" the thresholds stage absent; "/slide"
  /// the grip slide (GripSlideOptions' defaults); "/spline" and "/joint" the reach stage's
  /// method (PlanReach).
  SynthesisOptions Options() const;
};

/// Parses a StudyMethod::Label(); throws InputError naming the label and the part it does not
/// know otherwise.
StudyMethod ParseStudyMethod(const std::string& label);

}  // namespace graspsynth
