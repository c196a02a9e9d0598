#include "studies/study_method.hpp"

#include "common/errors.hpp"

namespace graspsynth {

std::string StudyMethod::Label() const {
  std::string label = ToString(method);
  if (refine && ceres && nlopt) label += "+refine";
  if (refine && ceres && !nlopt) label += "+ceres";
  if (refine && !ceres && nlopt) label += "+nlopt";
  if (resample == ResampleMode::kArcLength) label += "/arc";
  if (reach != ReachMethod::kAuto) label += std::string("/") + ToString(reach);
  if (!thresholds_from_sources) label += "/strict";
  if (grip_slide) label += "/slide";
  return label;
}

SynthesisOptions StudyMethod::Options() const {
  SynthesisOptions o;
  o.generation.method = method;
  o.generation.blend.resample = resample;
  if (!thresholds_from_sources) o.source_thresholds.reset();
  if (grip_slide) o.grip_slide = GripSlideOptions{};
  o.refinement_stages.clear();
  if (refine && ceres) o.refinement_stages.push_back(RefinementStage::kCeres);
  if (refine && nlopt) o.refinement_stages.push_back(RefinementStage::kNlopt);
  o.reach.method = reach;
  return o;
}

StudyMethod ParseStudyMethod(const std::string& label) {
  const auto fail = [&](const std::string& part) {
    return InputError("unknown method '" + label + "': '" + part +
                      "' is not known (a method interp, line or nearest, then optionally "
                      "+refine, +ceres or +nlopt, /arc, /spline or /joint, /strict, /slide (with "
                      "a refinement); e.g. "
                      "interp+refine/arc)");
  };
  StudyMethod m;
  m.refine = false;
  size_t end = label.find_first_of("+/");
  const std::string name = label.substr(0, end);
  try {
    m.method = ParseSynthesisMethod(name);
  } catch (const InputError&) {
    throw fail(name);
  }
  while (end != std::string::npos) {
    const size_t next = label.find_first_of("+/", end + 1);
    const std::string part = label.substr(end, next == std::string::npos ? next : next - end);
    if (part == "+refine" && !m.refine) {
      m.refine = true;
    } else if (part == "+ceres" && !m.refine) {
      m.refine = true;
      m.nlopt = false;
    } else if (part == "+nlopt" && !m.refine) {
      m.refine = true;
      m.ceres = false;
    } else if (part == "/arc" && m.resample == ResampleMode::kNormalizedTime) {
      m.resample = ResampleMode::kArcLength;
    } else if ((part == "/spline" || part == "/joint") && m.reach == ReachMethod::kAuto) {
      m.reach = ParseReachMethod(part.substr(1));
    } else if (part == "/strict" && m.thresholds_from_sources) {
      m.thresholds_from_sources = false;
    } else if (part == "/slide" && !m.grip_slide && m.refine) {
      m.grip_slide = true;
    } else {
      throw fail(part);
    }
    end = next;
  }
  if (m.Label() != label) throw fail(label);  // e.g. parts out of order
  return m;
}

}  // namespace graspsynth
