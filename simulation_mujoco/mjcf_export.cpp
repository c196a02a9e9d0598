#include "simulation_mujoco/mjcf_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/valid_options.hpp"
#include "scene/triangle_mesh.hpp"

namespace graspsynth {
namespace {

// How far outside a joint's range its limit lies, rad: as the ODE world's stops (servo targets
// lie inside the range, and a servo holding a joint at its limit would fight the limit).
constexpr double kLimitMargin = Radians(2.0);

// Collision bits, the ODE world's categories (simulation/detail/simulation_data_internal.hpp):
// MuJoCo tests contype and conaffinity as ODE tests category and collide bits.
// The table is two geoms: its top face as a plane for the object (MuJoCo 2.2's box-box
// contacts of the pan's foot on a box table blew up at some orientations; box-plane contacts
// are robust) and the box, kBitTableBox, for the robot.
constexpr unsigned kBitTable = 1, kBitHandle = 2, kBitArm = 4, kBitPalm = 8, kBitFinger = 16,
                   kBitPan = 32, kBitFoot = 64, kBitTableBox = 128;
constexpr unsigned kBitRobot = kBitArm | kBitPalm | kBitFinger;

// Numbers in full precision: the exported kinematics must match ours to roundoff.
std::string Num(double x) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", x);
  return text;
}

std::string Vec(const Eigen::Vector3d& v) {
  return Num(v.x()) + " " + Num(v.y()) + " " + Num(v.z());
}

// pos="..." quat="..." of a pose (MuJoCo's quaternions are w first).
std::string PoseAttributes(const Eigen::Isometry3d& X) {
  Eigen::Quaterniond q(X.linear());
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return "pos=\"" + Vec(X.translation()) + "\" quat=\"" + Num(q.w()) + " " + Num(q.x()) + " " +
         Num(q.y()) + " " + Num(q.z()) + "\"";
}

std::string InertialElement(double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& I) {
  return "<inertial pos=\"" + Vec(com) + "\" mass=\"" + Num(mass) + "\" fullinertia=\"" +
         Num(I(0, 0)) + " " + Num(I(1, 1)) + " " + Num(I(2, 2)) + " " + Num(I(0, 1)) + " " +
         Num(I(0, 2)) + " " + Num(I(1, 2)) + "\"/>";
}

// Writes the model's elements; keeps the geoms' names and roles.
class Writer {
 public:
  Writer(const SimulationModel& model, const MjcfOptions& options)
      : model_(model), options_(options) {}

  MjcfModel Write(const Placement& placement, const JointTrajectory* trajectory);

 private:
  const RobotModel& robot() const { return model_.robot(); }
  void Line(int depth, const std::string& text) {
    xml_ << std::string(2 * depth, ' ') << text << "\n";
  }
  void Header();
  void Assets();
  void Geom(int depth, const std::string& body, const CollisionShape& shape, MjcfRole role,
            int hand_index, unsigned contype, unsigned conaffinity, int priority, double friction,
            const std::string& link);
  void Shapes(int depth, const RigidLink& link, MjcfRole role, int hand_index);
  void OpenBody(int depth, const std::string& name, const Eigen::Isometry3d& X_PB,
                const LinkInertia& inertia);
  void Joint(int depth, const RevoluteJoint& joint, bool limited);
  void Robot();
  void Object(const Placement& placement);
  void Actuators();
  void FingerTablePairs();
  void Keyframes(const Eigen::Isometry3d& X_WO, const JointTrajectory& trajectory);
  unsigned HandConaffinity() const { return kBitHandle | kBitPan; }

  const SimulationModel& model_;
  const MjcfOptions& options_;
  std::ostringstream xml_;
  std::vector<MjcfGeom> geoms_;
  int geom_count_in_body_ = 0;
};

void Writer::Header() {
  const SimulationOptions& so = model_.options();
  const PhysicsVariation& pv = options_.physics;
  // contacts: ODE's spring-damper (kp, kd) on the object's mass m as MuJoCo's time constant
  // and damping ratio (docs/mujoco.md, "Contacts"): sqrt(m / kp) and kd / (2 sqrt(kp m)), the
  // time constant at least two steps (MuJoCo's own floor: a stiffer reference oscillates).
  const double m = model_.object_inertia().mass * pv.object_mass;
  const double kp = so.contact_kp * pv.contact_stiffness, kd = so.contact_kd * pv.contact_damping;
  const MjcfContact& c = options_.contact;
  const double time_constant =
      std::max(std::sqrt(m / kp), 2.0 * options_.time_step) * c.time_constant_scale;
  const std::string solref = Num(time_constant) + " " + Num(kd / (2.0 * std::sqrt(kp * m)));
  // MuJoCo's own settings in their shortest text (the defaults read as they always did).
  const std::string solimp = ShortestNumber(c.solimp_dmin) + " " + ShortestNumber(c.solimp_dmax) +
                             " " + ShortestNumber(c.solimp_width);
  Line(0, "<mujoco model=\"graspsynth\">");
  Line(1, "<compiler angle=\"radian\" inertiafromgeom=\"false\" balanceinertia=\"true\"/>");
  Line(1, "<option timestep=\"" + Num(options_.time_step) + "\" gravity=\"0 0 " + Num(-so.gravity) +
              "\" integrator=\"implicit\" cone=\"" + (c.pyramidal ? "pyramidal" : "elliptic") +
              "\" impratio=\"" + ShortestNumber(c.impratio) + "\"/>");
  Line(1, "<size njmax=\"4000\" nconmax=\"1000\"/>");
  Line(1, "<default>");
  Line(2, "<geom contype=\"0\" conaffinity=\"0\" condim=\"3\" solref=\"" + solref + "\" solimp=\"" +
              solimp + "\" rgba=\"0.7 0.7 0.7 1\"/>");
  Line(2, "<pair solref=\"" + solref + "\" solimp=\"" + solimp + "\"/>");
  Line(1, "</default>");
}

void Writer::Assets() {
  const ObjectModel& o = model_.scene().object;
  bool any = false;
  for (const ObjectPart& part : o.parts)
    any = any || part.shape.kind == CollisionShape::Kind::kMesh;
  if (!any) return;
  Line(1, "<asset>");
  for (const ObjectPart& part : o.parts) {
    if (part.shape.kind != CollisionShape::Kind::kMesh) continue;
    std::string vertex, face;
    for (const Eigen::Vector3d& v : part.shape.mesh->vertices) vertex += Vec(v) + " ";
    for (const std::array<int, 3>& t : part.shape.mesh->triangles) {
      face += std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + " ";
    }
    Line(2, "<mesh name=\"object_" + part.name + "\" vertex=\"" + vertex + "\" face=\"" + face +
                "\"/>");
  }
  Line(1, "</asset>");
}

void Writer::Geom(int depth, const std::string& body, const CollisionShape& shape, MjcfRole role,
                  int hand_index, unsigned contype, unsigned conaffinity, int priority,
                  double friction, const std::string& link) {
  const std::string name = body + "/" + std::to_string(geom_count_in_body_++);
  const Eigen::Vector3d& s = shape.size;
  std::string type;
  switch (shape.kind) {
    case CollisionShape::Kind::kBox:
      type = "type=\"box\" size=\"" + Vec(0.5 * s) + "\"";
      break;
    case CollisionShape::Kind::kCapsule:
      type = "type=\"capsule\" size=\"" + Num(s.x()) + " " + Num(0.5 * s.y()) + "\"";
      break;
    case CollisionShape::Kind::kCylinder:
      type = "type=\"cylinder\" size=\"" + Num(s.x()) + " " + Num(0.5 * s.y()) + "\"";
      break;
    case CollisionShape::Kind::kSphere:
      type = "type=\"sphere\" size=\"" + Num(s.x()) + "\"";
      break;
    case CollisionShape::Kind::kMesh:
      type = "type=\"mesh\" mesh=\"object_" + link + "\"";
      break;
  }
  Line(depth, "<geom name=\"" + name + "\" " + type + " " + PoseAttributes(shape.X_LG) +
                  " contype=\"" + std::to_string(contype) + "\" conaffinity=\"" +
                  std::to_string(conaffinity) + "\" priority=\"" + std::to_string(priority) +
                  "\" friction=\"" + Num(friction) + " 0.005 0.0001\"/>");
  geoms_.push_back(
      {name, role, role == MjcfRole::kObject ? model_.scene().object.name : link, hand_index});
}

// a robot link's shapes: the arm's (friction with the object: arm_object_friction, which its
// priority makes the pair's), the palm's and the fingers' (the object's friction rules).
void Writer::Shapes(int depth, const RigidLink& link, MjcfRole role, int hand_index) {
  const SimulationOptions& so = model_.options();
  for (const CollisionShape& shape : link.shapes) {
    if (role == MjcfRole::kArm) {
      Geom(depth, link.name, shape, role, -1, kBitArm, kBitTableBox | kBitHandle | kBitPan, 2,
           so.arm_object_friction, link.name);
    } else {
      // finger-table contacts are explicit pairs (FingerTablePairs) with their own friction.
      const unsigned bit = role == MjcfRole::kPalm ? kBitPalm : kBitFinger;
      const unsigned affinity =
          role == MjcfRole::kPalm ? kBitTable | HandConaffinity() : HandConaffinity();
      Geom(depth, link.name, shape, role, hand_index, bit, affinity, 0, 1.0, link.name);
    }
  }
}

void Writer::OpenBody(int depth, const std::string& name, const Eigen::Isometry3d& X_PB,
                      const LinkInertia& inertia) {
  geom_count_in_body_ = 0;
  Line(depth, "<body name=\"" + name + "\" " + PoseAttributes(X_PB) + ">");
  if (inertia.mass > 0.0)
    Line(depth + 1, InertialElement(inertia.mass, inertia.p_LCm, inertia.I_Cm));
}

void Writer::Joint(int depth, const RevoluteJoint& joint, bool limited) {
  std::string text =
      "<joint name=\"" + joint.name + "\" type=\"hinge\" axis=\"" + Vec(joint.axis_J) + "\"";
  if (limited) {
    text += " limited=\"true\" range=\"" + Num(joint.lower - kLimitMargin) + " " +
            Num(joint.upper + kLimitMargin) + "\"";
  }
  Line(depth, text + "/>");
}

void Writer::Robot() {
  const RobotModel& r = robot();
  geom_count_in_body_ = 0;
  for (const CollisionShape& shape : r.arm.base().shapes) {
    Geom(2, r.arm.base().name, shape, MjcfRole::kArm, -1, kBitArm,
         kBitTableBox | kBitHandle | kBitPan, 2, model_.options().arm_object_friction,
         r.arm.base().name);
  }
  int depth = 2;
  for (int i = 1; i <= kArmDof; ++i, ++depth) {
    const RevoluteJoint& j = r.arm.joint(i - 1);
    OpenBody(depth, r.arm.link(i).name, j.X_PJ, r.arm.link(i).inertia);
    // limits only where the range lies inside (-pi, pi), as the ODE world's stops.
    Joint(depth + 1, j, j.upper < M_PI - 1e-6 && j.lower > -M_PI + 1e-6);
    Shapes(depth + 1, r.arm.link(i), MjcfRole::kArm, -1);
  }
  OpenBody(depth, r.hand.mount().name, r.X_FH, r.hand.mount().inertia);
  const int palm = r.hand.joint_count();  // the palm's and mount's hand index
  Shapes(depth + 1, r.hand.mount(), MjcfRole::kPalm, palm);
  OpenBody(depth + 1, r.hand.palm().name, r.hand.X_HP(), r.hand.palm().inertia);
  Shapes(depth + 2, r.hand.palm(), MjcfRole::kPalm, palm);
  for (int f = 0; f < r.hand.finger_count(); ++f) {
    const Finger& finger = r.hand.finger(f);
    const int joints = static_cast<int>(finger.joints.size());
    for (int k = 0; k < joints; ++k) {
      const size_t kk = static_cast<size_t>(k);
      OpenBody(depth + 2 + k, finger.links[kk].name, finger.joints[kk].joint.X_PJ,
               finger.links[kk].inertia);
      Joint(depth + 3 + k, finger.joints[kk].joint, true);
      Shapes(depth + 3 + k, finger.links[kk], MjcfRole::kFinger, r.hand.JointIndex(f, k));
    }
    for (int k = joints - 1; k >= 0; --k) Line(depth + 2 + k, "</body>");
  }
  Line(depth + 1, "</body>");
  Line(depth, "</body>");
  for (--depth; depth >= 2; --depth) Line(depth, "</body>");
}

void Writer::Object(const Placement& placement) {
  const ObjectModel& o = model_.scene().object;
  const ObjectInertia& oi = model_.object_inertia();
  const PhysicsVariation& pv = options_.physics;
  Line(2, "<body name=\"object\" " + PoseAttributes(model_.scene().ObjectPose(placement)) + ">");
  Line(3, "<freejoint name=\"object\"/>");
  Line(3, InertialElement(oi.mass * pv.object_mass, oi.p_OC + pv.object_com_offset,
                          oi.I_C * pv.object_mass));
  geom_count_in_body_ = 0;
  for (const ObjectPart& part : o.parts) {
    const unsigned bit = part.touches == PartContact::kTable   ? kBitFoot
                         : part.touches == PartContact::kRobot ? kBitPan
                                                               : kBitHandle;
    const unsigned affinity = bit == kBitFoot  ? kBitTable
                              : bit == kBitPan ? kBitRobot
                                               : kBitTable | kBitRobot;
    Geom(3, "object", part.shape, MjcfRole::kObject, -1, bit, affinity, 1,
         part.friction * pv.object_hand_friction, part.name);
  }
  Line(2, "</body>");
}

// one servo per joint (the file comment of mjcf_export.hpp): arm joints S1..W2, then every
// hand joint in HandJointVector order (20 for the Gifu).
void Writer::Actuators() {
  const SimulationOptions& so = model_.options();
  const RobotModel& r = robot();
  Line(1, "<actuator>");
  auto servo = [&](const std::string& joint, double effort, double gain, MujocoServo mapping) {
    const double kv = effort / SaturationVelocity(mapping);
    const double kp = gain * kv;
    Line(2, "<general name=\"" + joint + "\" joint=\"" + joint + "\" gainprm=\"" + Num(kp) +
                "\" biastype=\"affine\" biasprm=\"0 " + Num(-kp) + " " + Num(-kv) +
                "\" forcelimited=\"true\" forcerange=\"" + Num(-effort) + " " + Num(effort) +
                "\"/>");
  };
  for (int i = 0; i < kArmDof; ++i) {
    servo(r.arm.joint(i).name, r.arm.max_effort()[i], so.arm_servo_gain, MujocoServo::kStiff);
  }
  for (int j = 0; j < r.hand.joint_count(); ++j) {
    const RevoluteJoint& joint = r.hand.joint(j).joint;
    servo(joint.name, joint.max_effort * so.hand_effort_scale * options_.physics.hand_effort,
          so.finger_servo_gain, options_.servo);
  }
  Line(1, "</actuator>");
}

// finger-table contacts with the ODE world's hand_table_friction (the table's own coefficient
// is the object's); the palm's are reported only, as in ODE (a trial ends there).
void Writer::FingerTablePairs() {
  const double mu = model_.options().hand_table_friction;
  Line(1, "<contact>");
  for (const MjcfGeom& g : geoms_) {
    if (g.role != MjcfRole::kFinger) continue;
    Line(2, "<pair geom1=\"table\" geom2=\"" + g.name + "\" condim=\"3\" friction=\"" + Num(mu) +
                " " + Num(mu) + " 0.005 0.0001 0.0001\"/>");
  }
  Line(1, "</contact>");
}

// one keyframe per trajectory sample: the robot at the commanded joints, the object at rest,
// ctrl the servo targets (each DIP's is its PIP's), time the sample's.
void Writer::Keyframes(const Eigen::Isometry3d& X_WO, const JointTrajectory& trajectory) {
  const Eigen::Quaterniond q(X_WO.linear());
  const std::string object = Vec(X_WO.translation()) + " " + Num(q.w()) + " " + Num(q.x()) + " " +
                             Num(q.y()) + " " + Num(q.z());
  Line(1, "<keyframe>");
  for (const TrajectorySample& s : trajectory.samples) {
    std::string joints;
    for (int i = 0; i < kArmDof; ++i) joints += Num(s.arm[i]) + " ";
    const HandJointVector h = HandJointPositions(robot().hand, s.hand);
    for (int j = 0; j < robot().hand.joint_count(); ++j) joints += Num(h[j]) + " ";
    Line(2, "<key time=\"" + Num(s.t) + "\" qpos=\"" + joints + object + "\" ctrl=\"" + joints +
                "\"/>");
  }
  Line(1, "</keyframe>");
}

MjcfModel Writer::Write(const Placement& placement, const JointTrajectory* trajectory) {
  const TableModel& t = model_.scene().table;
  Header();
  Assets();
  Line(1, "<worldbody>");
  Line(2, "<light pos=\"0 0 3\" dir=\"0 0 -1\"/>");
  const std::string table_friction = "\" priority=\"2\" friction=\"" +
                                     Num(t.friction * options_.physics.object_table_friction) +
                                     " 0.005 0.0001\"";
  Line(2, "<geom name=\"table\" type=\"box\" size=\"" + Vec(0.5 * t.size) + "\" pos=\"" +
              Num(t.centre_xy.x()) + " " + Num(t.centre_xy.y()) + " " +
              Num(t.top_z - 0.5 * t.size.z()) + "\" contype=\"" + std::to_string(kBitTableBox) +
              "\" conaffinity=\"" + std::to_string(kBitArm | kBitPalm) + table_friction +
              " rgba=\"0.6 0.45 0.3 1\"/>");
  Line(2, "<geom name=\"table_top\" type=\"plane\" size=\"" + Num(0.5 * t.size.x()) + " " +
              Num(0.5 * t.size.y()) + " 0.05\" pos=\"" + Num(t.centre_xy.x()) + " " +
              Num(t.centre_xy.y()) + " " + Num(t.top_z) + "\" contype=\"" +
              std::to_string(kBitTable) + "\" conaffinity=\"" +
              std::to_string(kBitHandle | kBitFoot) + table_friction + " rgba=\"0 0 0 0\"/>");
  geoms_.push_back({"table", MjcfRole::kTable, "table", -1});
  geoms_.push_back({"table_top", MjcfRole::kTable, "table", -1});
  Robot();
  Object(placement);
  Line(1, "</worldbody>");
  FingerTablePairs();
  Actuators();
  if (trajectory) Keyframes(model_.scene().ObjectPose(placement), *trajectory);
  Line(0, "</mujoco>");
  return {xml_.str(), geoms_};
}

}  // namespace

std::string_view ToString(MujocoServo servo) {
  return servo == MujocoServo::kStiff ? "stiff" : "soft";
}

MujocoServo ParseMujocoServo(std::string_view text, std::string_view what) {
  if (text == "stiff") return MujocoServo::kStiff;
  if (text == "soft") return MujocoServo::kSoft;
  throw InputError(std::string(what) + ": '" + std::string(text) +
                   "' is not a servo mapping (stiff or soft)");
}

double SaturationVelocity(MujocoServo servo) { return servo == MujocoServo::kStiff ? 0.01 : 0.5; }

bool MjcfOptions::IsValid(std::string* why) const {
  if (!(std::isfinite(time_step) && time_step > 0.0 && time_step <= 0.02)) {
    if (why) *why = "time_step (s, in (0, 0.02]) = " + std::to_string(time_step);
    return false;
  }
  return physics.IsValid(why) && contact.IsValid(why);
}

bool MjcfContact::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (!(std::isfinite(time_constant_scale) && time_constant_scale > 0.0))
    return fail("contact time_constant_scale (> 0) = " + std::to_string(time_constant_scale));
  if (!(solimp_dmin > 0.0 && solimp_dmin <= solimp_dmax && solimp_dmax < 1.0))
    return fail("contact solimp dmin, dmax (0 < dmin <= dmax < 1) = " +
                std::to_string(solimp_dmin) + ", " + std::to_string(solimp_dmax));
  if (!(std::isfinite(solimp_width) && solimp_width > 0.0))
    return fail("contact solimp width (m, > 0) = " + std::to_string(solimp_width));
  if (!(std::isfinite(impratio) && impratio >= 1.0))
    return fail("contact impratio (>= 1) = " + std::to_string(impratio));
  return true;
}

MjcfModel ExportMjcf(const SimulationModel& model, const Placement& placement,
                     const MjcfOptions& options, const JointTrajectory* trajectory) {
  RequireValid(options, "invalid MJCF option");
  if (trajectory && trajectory->samples.empty()) throw InputError("the trajectory has no samples");
  Writer writer(model, options);
  return writer.Write(placement, trajectory);
}

}  // namespace graspsynth
