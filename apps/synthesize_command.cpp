// graspsynth synthesize: a grasp for an object orientation from the grasp library, through the
// physics gate, written as a graspsynth-grasp/1 file.

#include "apps/synthesize_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "apps/cli_helpers.hpp"
#include "common/errors.hpp"
#include "learning_data/grasp_library.hpp"
#include "simulation/simulation_model.hpp"
#include "solver/grasp_file.hpp"
#include "solver/physics_gate.hpp"
#include "solver/synthesis.hpp"
#include "solver/validated_synthesis.hpp"

namespace graspsynth::apps {
namespace {

struct SynthesizeOptions {
  std::string library;
  double theta = NAN;
  std::string at;  // --at X,Y
  std::string method = "interp";
  std::string reach = "auto";
  double clearance_margin = 0.005;
  bool strict_thresholds = false;
  bool grip_slide = false;
  bool no_refine = false;
  std::string start;
  uint64_t seed = PhysicsGateOptions{}.seed;
  int perturb = PhysicsGateOptions{}.perturbations;
  int threads = PhysicsGateOptions{}.threads;
  double min_robustness = PhysicsGateOptions{}.min_robustness;
  bool force = false;
  bool no_physics_fallback = false;
  std::string out;
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
  PhysicsPerturbationOptions physics = PhysicsGateOptions{}.perturbation.physics;
};

Vector7d ParseStart(const std::string& text) {
  Vector7d q;
  std::stringstream ss(text);
  std::string item;
  int i = 0;
  while (std::getline(ss, item, ',')) {
    if (i >= kArmDof) break;
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v)) {
      throw InputError("--start: value " + std::to_string(i + 1) + " '" + item +
                       "' is not a finite number (radians)");
    }
    q[i++] = v;
  }
  if (i != kArmDof || std::getline(ss, item, ',')) {
    throw InputError("--start needs exactly 7 comma-separated joint values in radians, got '" +
                     text + "'");
  }
  return q;
}

int RunSynthesize(const SynthesizeOptions& o) {
  const SynthesisMethod method = ParseSynthesisMethod(o.method);
  if (!std::isfinite(o.theta)) throw InputError("--theta must be a finite number of degrees");
  const std::optional<Eigen::Vector2d> at = ParseAt(o.at);
  SceneModel scene = LoadScene(o.scene, o.object, kSynthesisNeedsHandle);
  const std::filesystem::path library_path = o.library.empty()
                                                 ? DefaultGraspLibraryPath(scene.object.name)
                                                 : std::filesystem::path(o.library);
  GraspLibrary library = ReadGraspLibrary(library_path);
  const SimulationModel sim(LoadRobotModel(o.robot.empty() ? DefaultRobotDescriptionPath()
                                                           : std::filesystem::path(o.robot)),
                            std::move(scene));
  SynthesisModel model(sim.robot(), sim.scene(), std::move(library));

  SynthesisOptions so;
  so.generation.method = method;
  if (o.no_refine) so.refinement_stages.clear();
  so.reach.method = ParseReachMethod(o.reach);
  so.refinement.clearance_margin = o.clearance_margin;
  if (o.strict_thresholds) so.source_thresholds.reset();
  if (o.grip_slide) {
    if (o.no_refine) throw InputError("--grip-slide needs the refinement (drop --no-refine)");
    so.grip_slide = GripSlideOptions{};
  }
  if (!o.start.empty()) so.start = ParseStart(o.start);
  ValidatedSynthesisOptions vo;
  vo.synthesis = so;
  vo.physics_fallback = !o.no_physics_fallback;
  vo.gate.perturbations = o.perturb;
  vo.gate.seed = o.seed;
  vo.gate.threads = o.threads;
  vo.gate.min_robustness = o.min_robustness;
  CheckPhysicsFlags(o.physics);
  vo.gate.perturbation.physics = o.physics;
  std::string why;
  if (!vo.gate.IsValid(&why)) throw InputError("bad physics gate option: " + why);
  SynthesisData data(model);
  const ValidatedSynthesis v =
      SynthesizeAndValidate(sim, model, MakeSynthesisTask(model.scene(), o.theta, at), vo, &data);
  const SynthesisResult& s = v.synthesis;
  switch (s.status) {
    case SynthesisStatus::kOk:
      break;
    case SynthesisStatus::kOutOfRange:
    case SynthesisStatus::kBadStart:
    case SynthesisStatus::kNoModel:
      throw InputError(s.message);
    case SynthesisStatus::kUnreachable:
      std::cerr << "graspsynth synthesize: no grasp: " << s.message << " (nothing written)\n";
      return 1;
  }
  if (!v.rejected_blend.empty()) {
    std::cerr << "the blend failed its nominal trial in physics: " << v.rejected_blend << "\n";
  }
  if (!v.rejected_slide.empty()) {
    std::cerr << "the slid grip failed its nominal trial in physics, so the grip was not slid: "
              << v.rejected_slide << "\n";
  }
  std::cerr << "synthesized theta " << o.theta << " deg"
            << (at ? " at (" + std::to_string(at->x()) + ", " + std::to_string(at->y()) + ") m"
                   : std::string())
            << " by " << ToString(s.used)
            << (s.fallback ? " (fallback: " + s.fallback_reason.Text() + ")" : std::string())
            << ": " << s.trajectory.samples.size() << " samples, " << s.trajectory.duration()
            << " s; " << ToString(s.reach_used) << " reach (" << s.reach_reason << "); "
            << "generate " << s.generate_s * 1e3 << " ms, refine " << s.refine_s * 1e3
            << " ms, joints " << s.joints_s * 1e3 << " ms\n";
  if (s.refined) std::cerr << "refinement: " << s.refinement.BriefReport() << "\n";
  if (so.grip_slide && !std::isfinite(s.grip_radius)) {
    std::cerr << "grip slide: not run (the object has no handle, or the library no fitted line "
                 "principle to say where the hand holds it)\n";
  } else if (so.grip_slide) {
    std::cerr << "grip slide: the grip held the handle " << s.grip_radius * 1e3
              << " mm from the object's centre; slid " << s.grip_slide * 1e3 << " mm toward it"
              << (v.rejected_slide.empty() ? "" : " (the slid grip was rejected)") << "\n";
  }
  const PhysicsGateResult& gate = v.gate;
  std::cerr << "physics gate: " << (gate.passed ? "passed" : "FAILED") << ": " << gate.reason
            << "; quality: epsilon " << gate.quality.epsilon << ", volume " << gate.quality.volume
            << " (" << gate.contacts.size() << " contacts)\n";
  if (!gate.passed) {
    if (!o.force) {
      std::cerr << "graspsynth synthesize: the grasp failed the physics gate: " << gate.reason
                << " (nothing written; --force writes it with the failed validation)\n";
      return 1;
    }
    WriteGraspFile(o.out, s, &gate, true);
    std::cerr << "wrote " << o.out << " with the failed validation (--force)\n";
    return 1;
  }
  WriteGraspFile(o.out, s, &gate, o.force);
  std::cerr << "wrote " << o.out << "\n";
  return 0;
}

}  // namespace

void AddSynthesizeCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<SynthesizeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "synthesize",
      "Synthesize a grasp for an object orientation from the grasp library, check it in\n"
      "physics and write it as a graspsynth-grasp/1 file (its \"trajectory\" member is a\n"
      "graspsynth-trajectory/1 document; `graspsynth simulate grasp.json` plays it).\n"
      "Methods: interp (the paper's blend of the two nearest demonstrations; a bracket that\n"
      "cannot be blended falls back to the nearer demonstration turned with the object, then\n"
      "the line principle; a blend whose nominal trial fails in physics falls back the same\n"
      "way), line (the line principle, also outside the library's range),\n"
      "nearest (the nearest demonstration turned with the object).\n"
      "--at X,Y puts the object elsewhere on the table. With a library over placements\n"
      "(learning_data/placements/library.json) interp blends the demonstrations at the\n"
      "corners of the query's cell in a Delaunay triangulation of the demonstrated (x, y,\n"
      "theta); nearest moves and turns the nearest one with the object. Without --at the\n"
      "object stands at the scene's centre, and the grasp is made for it there.\n"
      "Example:\n"
      "  graspsynth synthesize --library learning_data/placements/library.json \\\n"
      "      --at -0.27,0.87 --theta 65 --out grasp.json");
  cmd->add_option("--library", opts->library,
                  "Grasp library (graspsynth-library/1, or /2 over placements)");
  cmd->add_option("--theta", opts->theta, "Object orientation, degrees")->required();
  AddAtFlag(cmd, &opts->at);
  cmd->add_option("--method", opts->method, "interp, line or nearest")
      ->check(CLI::IsMember({"interp", "line", "nearest"}))
      ->capture_default_str();
  cmd->add_flag("--no-refine", opts->no_refine, "Skip the Ceres and NLopt refinement");
  cmd->add_option("--reach", opts->reach,
                  "spline (the paper's Cartesian spline), joint (minimum-jerk joint move to the "
                  "pre-grasp configuration) or auto (the spline unless it passes within 1 cm of "
                  "the workspace's edge)")
      ->check(CLI::IsMember({"spline", "joint", "auto"}))
      ->capture_default_str();
  cmd->add_option("--clearance-margin", opts->clearance_margin,
                  "The refinement's clearance of hand and arm from object and table along the "
                  "approach, m")
      ->capture_default_str();
  cmd->add_flag("--strict-thresholds", opts->strict_thresholds,
                "Refine to the default clearance, penetration and contact thresholds even where "
                "the source demonstrations, which held the object in physics, break them");
  cmd->add_flag("--grip-slide", opts->grip_slide,
                "After the refinement, slide a grasp that holds the handle within 4 cm of its end "
                "in toward the object's centre (by up to 5 cm, then half and a quarter of it; the "
                "first that keeps the refinement's constraints and 2 cm between arm and object "
                "is kept; a slid grip whose nominal trial fails gives way to the unslid one)");
  cmd->add_option("--start", opts->start,
                  "Start arm configuration q1,...,q7 in radians (default: the rest pose for the "
                  "grasp orientation)");
  cmd->add_option("--seed", opts->seed, "Seed of the perturbed trials")->capture_default_str();
  cmd->add_option("--perturb", opts->perturb,
                  "Perturbed trials of the physics gate (0: nominal only)")
      ->capture_default_str();
  cmd->add_option("--threads", opts->threads, "Worker threads of the gate (0: all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--min-robustness", opts->min_robustness,
                  "Success fraction the gate needs under perturbation")
      ->capture_default_str();
  cmd->add_flag("--force", opts->force,
                "Write the grasp even when it fails the gate (with the failed validation)");
  cmd->add_option("--out", opts->out, "Output grasp file")->required();
  cmd->add_option("--robot", opts->robot, "Robot description (default: the shipped URDF)");
  cmd->add_option("--scene", opts->scene, "Scene description (default: models/scene.json)");
  AddObjectFlag(cmd, &opts->object);
  AddPhysicsFallbackFlag(cmd, &opts->no_physics_fallback);
  AddPhysicsPerturbationFlags(cmd, &opts->physics);
  cmd->callback([opts, exit_code] { *exit_code = RunSynthesize(*opts); });
}

}  // namespace graspsynth::apps
