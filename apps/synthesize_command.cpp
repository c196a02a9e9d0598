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
#include "apps/request_flags.hpp"
#include "common/errors.hpp"
#include "gate/grasp_file.hpp"
#include "gate/physics_gate.hpp"
#include "gate/validated_synthesis.hpp"
#include "kinematics/robot_file.hpp"
#include "learning_data/grasp_library.hpp"
#include "request/synthesize_request.hpp"
#include "simulation/simulation_model.hpp"
#include "solver/synthesis.hpp"

namespace graspsynth::apps {
namespace {

// The command's own options; the synthesis' are the request's (request/synthesize_request.hpp).
struct SynthesizeOptions {
  std::string library;
  bool force = false;
  std::string out;
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
};

int RunSynthesize(const SynthesizeOptions& o, const request::SynthesizeRequest& r) {
  const ValidatedSynthesisOptions vo = request::ToValidatedSynthesisOptions(r);
  const SynthesisOptions& so = vo.synthesis;
  SceneModel scene = LoadScene(o.scene, o.object, kSynthesisNeedsHandle);
  const std::filesystem::path library_path = o.library.empty()
                                                 ? DefaultGraspLibraryPath(scene.object.name)
                                                 : std::filesystem::path(o.library);
  GraspLibrary library = ReadGraspLibrary(library_path);
  const SimulationModel sim(LoadRobotOption(o.robot), std::move(scene));
  RequireDefaultRobot(sim.robot(), "--robot: synthesize", "a grasp library (graspsynth-library)");
  SynthesisModel model(sim.robot(), sim.scene(), std::move(library));
  const std::optional<Eigen::Vector2d>& at = r.at;
  SynthesisData data(model);
  const ValidatedSynthesis v =
      SynthesizeAndValidate(sim, model, MakeSynthesisTask(model.scene(), r.theta, at), vo, &data);
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
  std::cerr << "synthesized theta " << r.theta << " deg"
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
  std::cerr << "hold margin: " << HoldMarginBrief(gate.hold_margin)
            << (gate.hold_margin_shortfall.empty() ? "" : "; misses " + gate.hold_margin_shortfall)
            << (gate.hold_margin_options.require ? " (required)" : " (reported only)") << "\n";
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
      "Synthesize a grasp for an object orientation from the grasp library\n"
      "The grasp is checked in physics (the gate: a nominal trial and --perturb perturbed ones)\n"
      "and written as a graspsynth-grasp/1 file (its \"trajectory\" member is a\n"
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
  auto flags =
      std::make_shared<RequestFlags<request::SynthesizeRequest>>(cmd, request::SynthesizeOptions());
  cmd->add_option("--library", opts->library,
                  "Grasp library (graspsynth-library/1, or /2 over placements)");
  cmd->add_flag("--force", opts->force,
                "Write the grasp even when it fails the gate (with the failed validation)");
  cmd->add_option("--out", opts->out, "Output grasp file")->required();
  AddRobotOption(cmd, &opts->robot);
  cmd->add_option("--scene", opts->scene, "Scene description (default: models/scene.json)");
  AddObjectFlag(cmd, &opts->object);
  cmd->callback([opts, flags, exit_code] { *exit_code = RunSynthesize(*opts, flags->Build()); });
}

}  // namespace graspsynth::apps
