#include "simulation/simulation_model.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "common/errors.hpp"
#include "common/valid_options.hpp"
#include "scene/base_frame.hpp"
#include "simulation/trial_judge.hpp"

namespace graspsynth {
namespace {

bool Check(bool ok, const std::string& what, double value, std::string* why) {
  if (!ok && why) {
    std::ostringstream s;
    s << what << " = " << value;
    *why = s.str();
  }
  return ok;
}

bool Positive(double x) { return std::isfinite(x) && x > 0.0; }
bool NonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

}  // namespace

bool PhysicsVariation::IsValid(std::string* why) const {
  return Check(Positive(object_hand_friction), "object_hand_friction", object_hand_friction, why) &&
         Check(Positive(object_table_friction), "object_table_friction", object_table_friction,
               why) &&
         Check(Positive(contact_stiffness), "contact_stiffness", contact_stiffness, why) &&
         Check(Positive(contact_damping), "contact_damping", contact_damping, why) &&
         Check(Positive(object_mass), "object_mass", object_mass, why) &&
         Check(object_com_offset.allFinite() && object_com_offset.norm() <= 0.05,
               "object_com_offset (m, |offset| <= 0.05)", object_com_offset.norm(), why) &&
         Check(Positive(hand_effort), "hand_effort", hand_effort, why);
}

bool PhysicsVariation::IsNominal() const {
  return object_hand_friction == 1.0 && object_table_friction == 1.0 && contact_stiffness == 1.0 &&
         contact_damping == 1.0 && object_mass == 1.0 && object_com_offset.isZero(0.0) &&
         hand_effort == 1.0;
}

bool SimulationOptions::IsValid(std::string* why) const {
  return Check(Positive(erp) && erp <= 1.0, "erp", erp, why) &&
         Check(Positive(cfm) && cfm < 1.0, "cfm", cfm, why) &&
         Check(Positive(contact_kp), "contact_kp", contact_kp, why) &&
         Check(NonNegative(contact_kd), "contact_kd", contact_kd, why) &&
         Check(NonNegative(surface_layer) && surface_layer < 0.01, "surface_layer", surface_layer,
               why) &&
         Check(Positive(max_correcting_vel), "max_correcting_vel", max_correcting_vel, why) &&
         Check(max_contacts_per_pair >= 1 && max_contacts_per_pair <= 16, "max_contacts_per_pair",
               max_contacts_per_pair, why) &&
         Check(NonNegative(gravity), "gravity", gravity, why) &&
         Check(Positive(finger_servo_gain), "finger_servo_gain", finger_servo_gain, why) &&
         Check(Positive(arm_servo_gain), "arm_servo_gain", arm_servo_gain, why) &&
         Check(NonNegative(hand_table_friction), "hand_table_friction", hand_table_friction, why) &&
         Check(NonNegative(arm_object_friction), "arm_object_friction", arm_object_friction, why) &&
         Check(Positive(hand_effort_scale), "hand_effort_scale", hand_effort_scale, why);
}

SimulationModel::SimulationModel(RobotModel robot, SceneModel scene, SimulationOptions options)
    : robot_(std::move(robot)),
      scene_(SceneInBaseFrame(std::move(scene), robot_.X_WB)),
      options_(options) {
  RequireValid(options_, "invalid simulation option");
  // a trial's load share counts each finger's contacts by its name (kLoadShareGroups).
  for (const Finger& finger : robot_.hand.fingers()) {
    bool known = false;
    for (int k = 0; k < kLoadSharePalm; ++k) known = known || kLoadShareGroups[k] == finger.name;
    if (!known) {
      throw InputError(robot_.hand.source() + ": finger '" + finger.name +
                       "': a simulated hand's fingers must be named thumb, index, middle, ring "
                       "or little for now (the trials' load share is kept per such finger)");
    }
  }
  object_inertia_ = scene_.object.Inertia();
}

SimulationModel LoadDefaultSimulationModel(const SimulationOptions& options) {
  return SimulationModel(LoadRobotModel(DefaultRobotDescriptionPath()),
                         LoadSceneModel(DefaultSceneModelPath()), options);
}

}  // namespace graspsynth
