#include "kinematics/robot_description.hpp"

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>
#include <optional>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "kinematics/pose_math.hpp"
#include "kinematics/urdf_arm_chain.hpp"

namespace graspsynth {
namespace {

constexpr std::array<const char*, kArmDof> kArmJointNames = {"S1", "S2", "S3", "E1",
                                                             "E2", "W1", "W2"};
constexpr std::array<const char*, kArmDof + 1> kArmLinkNames = {
    "base_link", "S1_link", "S2_link", "S3_link", "E1_link", "E2_link", "W1_link", "W2_link"};
constexpr const char* kHandMountJoint = "hand_mount";
constexpr const char* kHandMountLink = "hand_mount_link";
constexpr const char* kPalmLink = "palm";
constexpr const char* kShippedRelativePath = "models/pa10_gifu3.urdf";

// urdfdom reports through console_bridge; while it parses, its messages are collected here
// instead of going to the console. One handler for the process, used under the parse mutex.
class CapturingOutputHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    std::string& sink = level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR ? errors_ : warnings_;
    if (!sink.empty()) sink += "; ";
    sink += text;
  }
  void Clear() {
    errors_.clear();
    warnings_.clear();
  }
  // the errors, or the warnings when there were no errors.
  const std::string& reason() const { return errors_.empty() ? warnings_ : errors_; }

 private:
  std::string errors_;
  std::string warnings_;
};

// The joint graph of a URDF: every joint joins two different links, no link is the child of
// two joints, and no chain of parents comes back to where it started. urdfdom builds its link
// tree with shared pointers before it checks this, and leaks the tree of a graph with a cycle
// (found by fuzz/urdf_fuzz.cpp); what it cannot parse as XML is left to it. Throws InputError
// naming the source, the joint and the links.
void CheckJointGraph(std::string_view urdf_xml, const std::string& source) {
  TiXmlDocument document;
  document.Parse(std::string(urdf_xml).c_str());
  const TiXmlElement* robot = document.Error() ? nullptr : document.FirstChildElement("robot");
  if (robot == nullptr) return;
  std::map<std::string, std::pair<std::string, std::string>> parent_of;  // child: parent, joint
  for (const TiXmlElement* joint = robot->FirstChildElement("joint"); joint != nullptr;
       joint = joint->NextSiblingElement("joint")) {
    const auto link_of = [&](const char* tag) -> std::string {
      const TiXmlElement* e = joint->FirstChildElement(tag);
      const char* link = e == nullptr ? nullptr : e->Attribute("link");
      return link == nullptr ? std::string() : std::string(link);
    };
    const char* name_attribute = joint->Attribute("name");
    const std::string name = name_attribute == nullptr ? "" : name_attribute;
    const std::string parent = link_of("parent"), child = link_of("child");
    if (parent.empty() || child.empty()) continue;  // urdfdom names what is missing
    const std::string at = source + ": joint '" + name + "'";
    if (parent == child) {
      throw InputError(at + ": its parent and its child are the same link '" + child + "'");
    }
    const auto [it, added] = parent_of.emplace(child, std::make_pair(parent, name));
    if (!added) {
      throw InputError(at + ": link '" + child + "' is already the child of joint '" +
                       it->second.second + "' (a link has one parent)");
    }
  }
  for (const auto& [start, unused] : parent_of) {
    std::string link = start;
    for (size_t steps = 0; parent_of.count(link) != 0; ++steps) {
      if (steps > parent_of.size()) {
        throw InputError(source + ": the joints make a loop through link '" + start +
                         "' (a robot description is a tree)");
      }
      link = parent_of.at(link).first;
    }
  }
}

// console_bridge's handler and log level are process-wide: one parse at a time swaps them.
urdf::ModelInterfaceSharedPtr ParseWithUrdfdom(std::string_view urdf_xml,
                                               const std::string& source) {
  CheckJointGraph(urdf_xml, source);
  static std::mutex parse_mutex;
  // never destroyed: console_bridge may keep a pointer to it as its "previous" handler.
  static CapturingOutputHandler* const handler_ptr = new CapturingOutputHandler;
  CapturingOutputHandler& handler = *handler_ptr;
  std::lock_guard<std::mutex> lock(parse_mutex);
  handler.Clear();
  console_bridge::OutputHandler* const previous_handler = console_bridge::getOutputHandler();
  const console_bridge::LogLevel previous_level = console_bridge::getLogLevel();
  console_bridge::useOutputHandler(&handler);
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
  urdf::ModelInterfaceSharedPtr model;
  std::string exception_text;
  try {
    model = urdf::parseURDF(std::string(urdf_xml));
  } catch (const std::exception& e) {
    exception_text = e.what();
  }
  console_bridge::setLogLevel(previous_level);
  console_bridge::useOutputHandler(previous_handler);
  if (!model) {
    std::string reason = handler.reason();
    if (!exception_text.empty()) reason += (reason.empty() ? "" : "; ") + exception_text;
    if (reason.empty()) reason = "urdfdom gave no reason";
    throw InputError(source + ": not a valid URDF robot description (urdfdom: " + reason + ")");
  }
  return model;
}

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  const Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  return PoseFrom(Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z),
                  q.normalized());
}

std::string Quoted(const std::string& name) { return "'" + name + "'"; }

const char* JointTypeName(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    case urdf::Joint::FIXED:
      return "fixed";
    default:
      return "unknown";
  }
}

// A link that a fixed joint adds to a body: a frame only (merging links is not supported yet).
bool IsFrameOnly(const urdf::Link& link) { return !link.inertial && link.collision_array.empty(); }

// the parsed description and the names of the links the model has used so far.
class Reader {
 public:
  Reader(const urdf::ModelInterface& model, std::string source)
      : model_(model), source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& what) const { throw InputError(source_ + ": " + what); }

  const urdf::Joint& Joint(const std::string& name, const std::string& role) const {
    const urdf::JointConstSharedPtr joint = model_.getJoint(name);
    if (!joint) Fail(role + " " + Quoted(name) + " is missing");
    return *joint;
  }

  const urdf::Link& Link(const std::string& name, const std::string& role) {
    const urdf::LinkConstSharedPtr link = model_.getLink(name);
    if (!link) Fail(role + " link " + Quoted(name) + " is missing");
    used_links_.insert(name);
    return *link;
  }

  void RequireParentChild(const urdf::Joint& joint, const std::string& role,
                          const std::string& parent, const std::string& child) const {
    if (joint.parent_link_name != parent || joint.child_link_name != child) {
      Fail(role + " " + Quoted(joint.name) + " connects " + Quoted(joint.parent_link_name) +
           " -> " + Quoted(joint.child_link_name) + "; it must connect " + Quoted(parent) + " -> " +
           Quoted(child));
    }
  }

  void RequireFixed(const urdf::Joint& joint, const std::string& role) const {
    if (joint.type != urdf::Joint::FIXED) {
      Fail(role + " " + Quoted(joint.name) + " is " + JointTypeName(joint.type) +
           "; it must be fixed");
    }
  }

  RevoluteJoint Revolute(const urdf::Joint& joint, const std::string& role) const {
    const std::string where = role + " " + Quoted(joint.name);
    if (joint.type == urdf::Joint::CONTINUOUS) {
      Fail(where + " is continuous; it must be revolute with position limits");
    }
    if (joint.type != urdf::Joint::REVOLUTE) {
      Fail(where + " is " + JointTypeName(joint.type) + "; it must be revolute");
    }
    if (!joint.limits) Fail(where + " has no <limit>");
    RevoluteJoint r;
    r.name = joint.name;
    r.X_PJ = ToIsometry(joint.parent_to_joint_origin_transform);
    r.axis_J = Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z);
    r.lower = joint.limits->lower;
    r.upper = joint.limits->upper;
    r.max_velocity = joint.limits->velocity;
    r.max_effort = joint.limits->effort;
    return r;
  }

  LinkInertia Inertia(const urdf::Link& link) const {
    const std::string where = "link " + Quoted(link.name);
    if (!link.inertial) Fail(where + " has no <inertial>; every body needs a positive mass");
    const urdf::Inertial& in = *link.inertial;
    if (!(in.mass > 0.0) || !std::isfinite(in.mass)) {
      std::ostringstream msg;
      msg << where << " needs a positive mass, has " << in.mass << " kg";
      Fail(msg.str());
    }
    Eigen::Matrix3d I;
    I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    const Eigen::Isometry3d X_LC = ToIsometry(in.origin);
    LinkInertia inertia;
    inertia.mass = in.mass;
    inertia.p_LCm = X_LC.translation();
    inertia.I_Cm = X_LC.linear() * I * X_LC.linear().transpose();
    // a physical inertia is positive definite and its principal moments obey the triangle
    // inequality; ODE refuses anything else.
    const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
    if (!I.allFinite() || !(m[0] > 0.0) || m[0] + m[1] < m[2] * (1.0 - 1e-9)) {
      std::ostringstream msg;
      msg << where << " has a non-physical inertia (principal moments " << m.transpose()
          << " kg m^2; they must be positive and satisfy the triangle inequality)";
      Fail(msg.str());
    }
    return inertia;
  }

  std::vector<CollisionShape> Shapes(const urdf::Link& link) const {
    const std::string where = "link " + Quoted(link.name);
    std::vector<CollisionShape> shapes;
    for (const urdf::CollisionSharedPtr& collision : link.collision_array) {
      if (!collision || !collision->geometry) Fail(where + " has a <collision> without geometry");
      CollisionShape shape;
      shape.X_LG = ToIsometry(collision->origin);
      const urdf::Geometry& g = *collision->geometry;
      switch (g.type) {
        case urdf::Geometry::BOX: {
          const auto& box = static_cast<const urdf::Box&>(g);
          shape.kind = CollisionShape::Kind::kBox;
          shape.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& cylinder = static_cast<const urdf::Cylinder&>(g);
          // the capsule convention of models/README.md.
          shape.kind = collision->name.starts_with("capsule") ? CollisionShape::Kind::kCapsule
                                                              : CollisionShape::Kind::kCylinder;
          shape.size = Eigen::Vector3d(cylinder.radius, cylinder.length, 0.0);
          break;
        }
        case urdf::Geometry::SPHERE: {
          const auto& sphere = static_cast<const urdf::Sphere&>(g);
          shape.kind = CollisionShape::Kind::kSphere;
          shape.size = Eigen::Vector3d(sphere.radius, 0.0, 0.0);
          break;
        }
        case urdf::Geometry::MESH:
          Fail(where +
               " has a mesh collision geometry; graspsynth uses primitives only (box, cylinder, "
               "sphere, capsule)");
        default:
          Fail(where + " has a collision geometry of an unknown type");
      }
      const Eigen::Vector3d& d = shape.size;
      bool positive = d[0] > 0.0;
      if (shape.kind == CollisionShape::Kind::kBox) positive = (d.array() > 0.0).all();
      if (shape.kind == CollisionShape::Kind::kCylinder) positive = positive && d[1] > 0.0;
      if (shape.kind == CollisionShape::Kind::kCapsule) positive = positive && d[1] >= 0.0;
      if (!positive || !shape.size.allFinite()) {
        Fail(where + " has a collision geometry with a zero, negative or non-finite size");
      }
      shapes.push_back(shape);
    }
    return shapes;
  }

  RigidLink Body(const std::string& name, const std::string& role) {
    const urdf::Link& link = Link(name, role);
    return RigidLink{link.name, Inertia(link), Shapes(link)};
  }

  // every link of the description must have been read: anything else would be silently
  // missing from the simulation and the collision checks.
  void RequireAllLinksUsed() const {
    for (const auto& [name, link] : model_.links_) {
      if (!used_links_.count(name)) {
        Fail("link " + Quoted(name) +
             " is not part of the PA-10-7C + Gifu Hand III model (models/README.md lists the "
             "links it reads)");
      }
    }
  }

  // every link with mass or collision geometry must have been read (RequireAllLinksUsed for a
  // robot file, which names its parts: frames elsewhere change nothing and are let be).
  void RequireAllBodiesUsed(const std::string& where) const {
    for (const auto& [name, link] : model_.links_) {
      if (!used_links_.count(name) && link && !IsFrameOnly(*link)) {
        throw InputError(where + ": expected every link of " + Quoted(source_) +
                         " with mass or collision geometry in the arm or the hand, found link " +
                         Quoted(name) + " in neither");
      }
    }
  }

  const urdf::ModelInterface& model() const { return model_; }
  const std::string& source() const { return source_; }

 private:
  const urdf::ModelInterface& model_;
  std::string source_;
  std::set<std::string> used_links_;
};

ArmModel ReadArm(Reader& reader, const std::string& source) {
  RigidLink base = reader.Body(kArmLinkNames[0], "arm");
  std::array<RevoluteJoint, kArmDof> joints;
  std::array<RigidLink, kArmDof> links;
  for (int i = 0; i < kArmDof; ++i) {
    const urdf::Joint& joint = reader.Joint(kArmJointNames[i], "arm joint");
    joints[i] = reader.Revolute(joint, "arm joint");
    if (joint.mimic) reader.Fail("arm joint " + Quoted(joint.name) + " must not have a <mimic>");
    reader.RequireParentChild(joint, "arm joint", kArmLinkNames[i], kArmLinkNames[i + 1]);
    links[i] = reader.Body(kArmLinkNames[i + 1], "arm");
  }
  return ArmModel(source, std::move(base), std::move(joints), std::move(links));
}

// the message prefix `where`, or the URDF's source when it is empty.
std::string Where(const std::string& where, const std::string& source) {
  return where.empty() ? source : where;
}

// The joints from link `top` down to link `bottom`, top first; throws InputError (`where`)
// when `bottom` is not below `top`. Both links must exist.
std::vector<const urdf::Joint*> PathJoints(const urdf::ModelInterface& model,
                                           const std::string& source, const std::string& top,
                                           const std::string& bottom, const std::string& where) {
  std::vector<const urdf::Joint*> path;
  std::string link = bottom;
  while (link != top) {
    const urdf::LinkConstSharedPtr l = model.getLink(link);
    if (!l->parent_joint) {
      throw InputError(where + ": expected a chain of joints from link " + Quoted(top) +
                       " down to link " + Quoted(bottom) + " in " + Quoted(source) +
                       ", found that " + Quoted(bottom) + " is not below " + Quoted(top) +
                       " (its root is " + Quoted(link) + ")");
    }
    path.push_back(l->parent_joint.get());
    link = l->parent_joint->parent_link_name;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

// The joints from `base` down to `flange`, base first; throws when `flange` is not below it.
std::vector<const urdf::Joint*> ChainJoints(const urdf::ModelInterface& model,
                                            const std::string& source, const ArmChainNames& names) {
  return PathJoints(model, source, names.base_link, names.flange_link,
                    Where(names.chain_where, source));
}

// Throws "<where>: expected a link of '<source>', found \"<name>\"" when the URDF lacks it.
void RequireLink(const urdf::ModelInterface& model, const std::string& source,
                 const std::string& name, const std::string& where) {
  if (!model.getLink(name)) {
    throw InputError(where + ": expected a link of " + Quoted(source) + ", found \"" + name + "\"");
  }
}

// The hand joints' names in the order the URDF document lists them (urdfdom keeps its joints
// by name, so the fingers' order is the document's).
std::vector<std::string> JointsInDocumentOrder(std::string_view urdf_xml) {
  std::vector<std::string> names;
  TiXmlDocument document;
  document.Parse(std::string(urdf_xml).c_str());
  const TiXmlElement* robot = document.Error() ? nullptr : document.FirstChildElement("robot");
  if (robot == nullptr) return names;
  for (const TiXmlElement* joint = robot->FirstChildElement("joint"); joint != nullptr;
       joint = joint->NextSiblingElement("joint")) {
    const char* name = joint->Attribute("name");
    if (name != nullptr) names.emplace_back(name);
  }
  return names;
}

// The fingers' names: the revolute joints whose parent is the palm, in document order, each
// named <finger>_j1.
std::vector<std::string> FingerNames(const Reader& reader, std::string_view urdf_xml) {
  std::vector<std::string> fingers;
  for (const std::string& name : JointsInDocumentOrder(urdf_xml)) {
    const urdf::JointConstSharedPtr joint = reader.model().getJoint(name);
    if (!joint || joint->parent_link_name != kPalmLink || joint->type == urdf::Joint::FIXED) {
      continue;
    }
    const std::string suffix = "_j1";
    if (name.size() <= suffix.size() || name.compare(name.size() - 3, 3, suffix) != 0) {
      reader.Fail("hand joint " + Quoted(name) +
                  " on the palm must be a finger's first joint, named <finger>_j1");
    }
    fingers.push_back(name.substr(0, name.size() - suffix.size()));
  }
  if (fingers.empty()) reader.Fail("the palm has no finger (no joint <finger>_j1 on 'palm')");
  return fingers;
}

// The chain of finger `name`: <name>_j1 on the palm, then <name>_j2, ... each on the child of
// the one before, as long as the URDF has them, then the fixed <name>_tip. A joint with a
// <mimic> is coupled to the joint it names; every other joint is actuated, numbered from
// `*actuated` on. Couplings name their source by joint name until every finger is read
// (`*mimics`: joint name -> source joint name).
Finger ReadFinger(Reader& reader, const std::string& name, int* actuated,
                  std::map<std::string, const urdf::Joint*>* mimics) {
  Finger finger;
  finger.name = name;
  std::string parent = kPalmLink;
  for (int k = 0;; ++k) {
    const std::string joint_name = name + "_j" + std::to_string(k + 1);
    if (k > 0 && !reader.model().getJoint(joint_name)) break;
    const urdf::Joint& joint = reader.Joint(joint_name, "hand joint");
    HandJoint hj;
    hj.joint = reader.Revolute(joint, "hand joint");
    if (joint.parent_link_name != parent) {
      reader.Fail(
          "hand joint " + Quoted(joint_name) + " has parent link " +
          Quoted(joint.parent_link_name) + "; it must be " + Quoted(parent) +
          (k == 0 ? " (the palm)" : " (the child of " + name + "_j" + std::to_string(k) + ")"));
    }
    if (joint.mimic) {
      (*mimics)[joint_name] = &joint;
    } else {
      hj.actuated = (*actuated)++;
    }
    finger.joints.push_back(std::move(hj));
    finger.links.push_back(reader.Body(joint.child_link_name, "hand"));
    parent = joint.child_link_name;
  }
  const std::string tip_joint = name + "_tip";
  const urdf::Joint& tip = reader.Joint(tip_joint, "fingertip joint");
  reader.RequireFixed(tip, "fingertip joint");
  if (tip.parent_link_name != parent) {
    reader.Fail("fingertip joint " + Quoted(tip_joint) + " has parent link " +
                Quoted(tip.parent_link_name) + "; it must be the distal link " + Quoted(parent) +
                " (is joint " + Quoted(name + "_j" + std::to_string(finger.joints.size() + 1)) +
                " missing?)");
  }
  const urdf::Link& tip_link = reader.Link(tip.child_link_name, "fingertip");
  if (tip_link.inertial || !tip_link.collision_array.empty() || !tip_link.child_joints.empty()) {
    reader.Fail("fingertip frame " + Quoted(tip_link.name) +
                " must be a frame only: no <inertial>, no <collision>, no child joints");
  }
  finger.tip_name = tip_link.name;
  finger.X_LT = ToIsometry(tip.parent_to_joint_origin_transform);
  return finger;
}

// The fingers in document order, their actuated joints numbered in that order (the Gifu's
// f0..f15: thumb j1..j4, then j1..j3 of index, middle, ring, little) and each <mimic> a coupling
// (q = multiplier * q_source + offset) to the hand joint it names, which must be actuated.
std::vector<Finger> ReadFingers(Reader& reader, std::string_view urdf_xml) {
  std::vector<Finger> fingers;
  int actuated = 0;
  std::map<std::string, const urdf::Joint*> mimics;
  for (const std::string& name : FingerNames(reader, urdf_xml)) {
    fingers.push_back(ReadFinger(reader, name, &actuated, &mimics));
  }
  std::map<std::string, std::pair<int, const HandJoint*>> index;  // joint name: index, joint
  int j = 0;
  for (const Finger& finger : fingers) {
    for (const HandJoint& hj : finger.joints) index[hj.joint.name] = {j++, &hj};
  }
  for (Finger& finger : fingers) {
    for (HandJoint& hj : finger.joints) {
      const auto mimic = mimics.find(hj.joint.name);
      if (mimic == mimics.end()) continue;
      const urdf::JointMimic& m = *mimic->second->mimic;
      const auto source = index.find(m.joint_name);
      if (source == index.end() || !source->second.second->is_actuated()) {
        reader.Fail("hand joint " + Quoted(hj.joint.name) + " mimics " + Quoted(m.joint_name) +
                    "; it must mimic an actuated hand joint (one without a <mimic>)");
      }
      hj.coupling = JointCoupling{source->second.first, m.multiplier, m.offset};
    }
  }
  return fingers;
}

// The arm chain of names.base_link .. names.flange_link (ReadArmChain).
ArmChain ReadArmChainFrom(Reader& reader, const ArmChainNames& names) {
  const urdf::ModelInterface& model = reader.model();
  const std::string& source = reader.source();
  RequireLink(model, source, names.base_link, Where(names.base_where, source));
  RequireLink(model, source, names.flange_link, Where(names.flange_where, source));
  const std::vector<const urdf::Joint*> chain = ChainJoints(model, source, names);
  const std::string at = Where(names.chain_where, source) + ": expected ";
  const std::string between = " from link " + Quoted(names.base_link) + " to link " +
                              Quoted(names.flange_link) + " in " + Quoted(source);

  std::vector<std::string> revolute;
  for (const urdf::Joint* joint : chain) {
    if (joint->type == urdf::Joint::REVOLUTE) {
      revolute.push_back(joint->name);
    } else if (joint->type != urdf::Joint::FIXED) {
      throw InputError(at + "revolute and fixed joints only" + between + ", found joint " +
                       Quoted(joint->name) + " (" + JointTypeName(joint->type) + ")");
    }
  }
  if (revolute.size() != static_cast<size_t>(kArmDof)) {
    std::string list;
    for (const std::string& name : revolute) list += (list.empty() ? "" : ", ") + Quoted(name);
    throw InputError(at + std::to_string(kArmDof) + " revolute joints (and any fixed ones)" +
                     between + ", found " + std::to_string(revolute.size()) +
                     (list.empty() ? "" : " (" + list + ")"));
  }

  ArmChain arm;
  arm.base = reader.Body(names.base_link, "arm base");
  Eigen::Isometry3d X_fixed = Eigen::Isometry3d::Identity();  // fixed joints since the last link
  int i = 0;
  for (const urdf::Joint* joint : chain) {
    if (joint->type == urdf::Joint::FIXED) {
      X_fixed = X_fixed * ToIsometry(joint->parent_to_joint_origin_transform);
      const urdf::Link& link = reader.Link(joint->child_link_name, "arm");
      if (!IsFrameOnly(link)) {
        throw InputError(at +
                         "massless frames without collision geometry at the links of fixed "
                         "joints" +
                         between + ", found link " + Quoted(link.name) +
                         " with mass or collision geometry (merging links is not supported yet)");
      }
      continue;
    }
    if (joint->mimic) reader.Fail("arm joint " + Quoted(joint->name) + " must not have a <mimic>");
    arm.joints[i] = reader.Revolute(*joint, "arm joint");
    arm.joints[i].X_PJ = X_fixed * arm.joints[i].X_PJ;
    arm.links[i] = reader.Body(joint->child_link_name, "arm");
    X_fixed = Eigen::Isometry3d::Identity();
    ++i;
  }
  arm.X_7F = X_fixed;
  return arm;
}

// The pose of link `bottom` in link `top` through fixed joints only, each link between them a
// frame only. Throws InputError (`where`) otherwise, or when `bottom` is not below `top`.
Eigen::Isometry3d FixedPath(Reader& reader, const std::string& top, const std::string& bottom,
                            const std::string& where) {
  const std::string between = " from link " + Quoted(top) + " down to link " + Quoted(bottom) +
                              " in " + Quoted(reader.source());
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (const urdf::Joint* joint : PathJoints(reader.model(), reader.source(), top, bottom, where)) {
    if (joint->type != urdf::Joint::FIXED) {
      throw InputError(where + ": expected fixed joints only" + between + ", found joint " +
                       Quoted(joint->name) + " (" + JointTypeName(joint->type) + ")");
    }
    X = X * ToIsometry(joint->parent_to_joint_origin_transform);
    if (joint->child_link_name == bottom) break;
    if (!IsFrameOnly(reader.Link(joint->child_link_name, "hand"))) {
      throw InputError(where + ": expected massless frames without collision geometry" + between +
                       ", found link " + Quoted(joint->child_link_name) +
                       " with mass or collision geometry (merging links is not supported yet)");
    }
  }
  return X;
}

// The fingertip frame of a finger whose last joint's link is `distal`: its name and its pose in
// `distal`.
std::pair<std::string, Eigen::Isometry3d> ReadNamedTip(Reader& reader, const FingerPartNames& names,
                                                       const std::string& distal) {
  RequireLink(reader.model(), reader.source(), names.tip_link, names.tip_where);
  const urdf::Link& tip = reader.Link(names.tip_link, "fingertip");
  const urdf::Joint* joint = tip.parent_joint.get();
  if (joint == nullptr || joint->type != urdf::Joint::FIXED || joint->parent_link_name != distal) {
    throw InputError(
        names.tip_where + ": expected a link fixed to link " + Quoted(distal) +
        " (the child of joint " + Quoted(names.joints.back()) + "), found \"" + tip.name + "\"" +
        (joint == nullptr ? std::string(" (the root)")
                          : " (joint " + Quoted(joint->name) + ", " + JointTypeName(joint->type) +
                                ", on link " + Quoted(joint->parent_link_name) + ")"));
  }
  if (!IsFrameOnly(tip) || !tip.child_joints.empty()) {
    throw InputError(names.tip_where +
                     ": expected a frame only (no <inertial>, no <collision>, no child joints), "
                     "found link \"" +
                     tip.name + "\" with " +
                     (tip.inertial
                          ? "<inertial>"
                          : (!tip.collision_array.empty() ? "<collision>" : "child joints")));
  }
  return {tip.name, ToIsometry(joint->parent_to_joint_origin_transform)};
}

// A coupling read so far: the joint it follows by name, and where it was named.
struct NamedCoupling {
  std::string follows;
  double ratio = 1.0, offset = 0.0;
  std::string where;
};

std::string CouplingText(const std::string& follows, double ratio, double offset) {
  std::ostringstream s;
  s.precision(17);
  s << "follows '" << follows << "', ratio " << ratio << ", offset " << offset << " rad";
  return s.str();
}

// Finger `names`: its joints from `palm` on, each the child of the one before, their links and
// its tip. Couplings from the file (`file_couplings`, by joint name) and the URDF's <mimic>s go
// to `*couplings`; the others are numbered from `*actuated` on.
Finger ReadNamedFinger(Reader& reader, const FingerPartNames& names, const std::string& palm,
                       const std::map<std::string, NamedCoupling>& file_couplings,
                       std::set<std::string>* seen, int* actuated,
                       std::map<std::string, NamedCoupling>* couplings) {
  Finger finger;
  finger.name = names.name;
  std::string parent = palm;
  for (size_t k = 0; k < names.joints.size(); ++k) {
    const std::string& name = names.joints[k];
    const std::string& where = names.joints_where[k];
    const urdf::JointConstSharedPtr joint = reader.model().getJoint(name);
    if (!joint) {
      throw InputError(where + ": expected a joint of " + Quoted(reader.source()) + ", found \"" +
                       name + "\"");
    }
    if (!seen->insert(name).second) {
      throw InputError(where + ": expected a joint that no finger names before, found \"" + name +
                       "\" again");
    }
    if (joint->parent_link_name != parent) {
      throw InputError(where + ": expected a joint on link " + Quoted(parent) +
                       (k == 0 ? " (hand.palm_link)"
                               : " (the child of joint " + Quoted(names.joints[k - 1]) + ")") +
                       ", found \"" + name + "\" on link " + Quoted(joint->parent_link_name));
    }
    HandJoint hj;
    hj.joint = reader.Revolute(*joint, "hand joint");
    const auto file = file_couplings.find(name);
    if (joint->mimic) {
      const urdf::JointMimic& m = *joint->mimic;
      const NamedCoupling mimic{m.joint_name, m.multiplier, m.offset, where};
      if (file != file_couplings.end() && (file->second.follows != mimic.follows ||
                                           std::abs(file->second.ratio - mimic.ratio) > 1e-12 ||
                                           std::abs(file->second.offset - mimic.offset) > 1e-12)) {
        throw InputError(
            file->second.where + ": expected the coupling of the URDF's <mimic> of " +
            Quoted(name) + " (" + CouplingText(mimic.follows, mimic.ratio, mimic.offset) +
            "), found " +
            CouplingText(file->second.follows, file->second.ratio, file->second.offset));
      }
      (*couplings)[name] = file != file_couplings.end() ? file->second : mimic;
    } else if (file != file_couplings.end()) {
      (*couplings)[name] = file->second;
    } else {
      hj.actuated = (*actuated)++;
    }
    finger.joints.push_back(std::move(hj));
    finger.links.push_back(reader.Body(joint->child_link_name, "hand"));
    parent = joint->child_link_name;
  }
  std::tie(finger.tip_name, finger.X_LT) = ReadNamedTip(reader, names, parent);
  return finger;
}

// Sets every coupled joint's coupling to the joint it follows, which must be an actuated hand
// joint; a loop of couplings is named joint by joint.
void ResolveCouplings(const std::map<std::string, NamedCoupling>& couplings,
                      std::vector<Finger>* fingers) {
  std::map<std::string, std::pair<int, bool>> index;  // joint name: index, actuated
  int j = 0;
  for (const Finger& finger : *fingers) {
    for (const HandJoint& hj : finger.joints) index[hj.joint.name] = {j++, hj.is_actuated()};
  }
  for (Finger& finger : *fingers) {
    for (HandJoint& hj : finger.joints) {
      const auto c = couplings.find(hj.joint.name);
      if (c == couplings.end()) continue;
      const NamedCoupling& coupling = c->second;
      const auto source = index.find(coupling.follows);
      if (source == index.end()) {
        throw InputError(coupling.where + ": expected " + Quoted(hj.joint.name) +
                         " to follow a joint of the hand, found \"" + coupling.follows + "\"");
      }
      if (!source->second.second) {
        // follow the couplings from this joint: back to it is a loop.
        std::string path = hj.joint.name, at = coupling.follows;
        bool loop = false;
        for (size_t steps = 0; steps <= couplings.size() && couplings.count(at); ++steps) {
          path += " -> " + at;
          if (at == hj.joint.name) {
            loop = true;
            break;
          }
          at = couplings.at(at).follows;
        }
        throw InputError(coupling.where + ": expected " + Quoted(hj.joint.name) +
                         " to follow an actuated joint, found \"" + coupling.follows +
                         "\", which is coupled itself" +
                         (loop ? " (the couplings make a loop: " + path + ")" : ""));
      }
      hj.coupling = JointCoupling{source->second.first, coupling.ratio, coupling.offset};
    }
  }
}

// The hand below the arm's flange link: the mount, the palm and the fingers of `names`.
void ReadHandParts(Reader& reader, const std::string& flange_link,
                   const std::set<std::string>& arm_links, const HandNames& names,
                   RobotParts* parts) {
  const std::string& source = reader.source();
  for (const auto& [link, where] : {std::pair(names.mount_link, names.mount_where),
                                    std::pair(names.palm_link, names.palm_where)}) {
    RequireLink(reader.model(), source, link, where);
    if (arm_links.count(link)) {
      throw InputError(where + ": expected a link of the hand, below arm.flange_link " +
                       Quoted(flange_link) + ", found \"" + link + "\", a link of the arm");
    }
  }
  parts->X_FH = FixedPath(reader, flange_link, names.mount_link, names.mount_where);
  parts->mount = reader.Body(names.mount_link, "hand mount");
  parts->X_HP = FixedPath(reader, names.mount_link, names.palm_link, names.palm_where);
  parts->palm = reader.Body(names.palm_link, "hand");
  std::map<std::string, NamedCoupling> file_couplings;
  for (const FingerPartNames& finger : names.fingers) {
    for (const CoupledJointNames& c : finger.coupled) {
      file_couplings[c.joint] = NamedCoupling{c.follows, c.ratio, c.offset, c.where};
    }
  }
  std::set<std::string> seen;
  std::map<std::string, NamedCoupling> couplings;
  int actuated = 0;
  for (const FingerPartNames& finger : names.fingers) {
    parts->fingers.push_back(ReadNamedFinger(reader, finger, names.palm_link, file_couplings, &seen,
                                             &actuated, &couplings));
  }
  ResolveCouplings(couplings, &parts->fingers);
}

}  // namespace

ArmChain ReadArmChain(std::string_view urdf_xml, const std::string& source,
                      const ArmChainNames& names) {
  const urdf::ModelInterfaceSharedPtr model = ParseWithUrdfdom(urdf_xml, source);
  Reader reader(*model, source);
  return ReadArmChainFrom(reader, names);
}

RobotParts ReadRobotParts(std::string_view urdf_xml, const std::string& source,
                          const ArmChainNames& arm, const HandNames& hand) {
  const urdf::ModelInterfaceSharedPtr model = ParseWithUrdfdom(urdf_xml, source);
  Reader reader(*model, source);
  RobotParts parts;
  parts.name = model->getName();
  parts.arm = ReadArmChainFrom(reader, arm);
  std::set<std::string> arm_links = {arm.base_link};
  for (const urdf::Joint* joint : ChainJoints(*model, source, arm)) {
    arm_links.insert(joint->child_link_name);
  }
  ReadHandParts(reader, arm.flange_link, arm_links, hand, &parts);
  reader.RequireAllBodiesUsed(hand.where);
  return parts;
}

RobotModel ParseRobotModel(std::string_view urdf_xml, const std::string& source) {
  const urdf::ModelInterfaceSharedPtr model = ParseWithUrdfdom(urdf_xml, source);
  Reader reader(*model, source);

  const urdf::LinkConstSharedPtr root = model->getRoot();
  if (!root || root->name != kArmLinkNames[0]) {
    reader.Fail("the root link is " + Quoted(root ? root->name : std::string()) +
                "; the description must start at the arm's " + Quoted(kArmLinkNames[0]));
  }

  ArmModel arm = ReadArm(reader, source);

  const urdf::Joint& mount = reader.Joint(kHandMountJoint, "hand mount joint");
  reader.RequireFixed(mount, "hand mount joint");
  reader.RequireParentChild(mount, "hand mount joint", kArmLinkNames[kArmDof], kHandMountLink);
  const Eigen::Isometry3d X_FH = ToIsometry(mount.parent_to_joint_origin_transform);
  RigidLink mount_link = reader.Body(kHandMountLink, "hand mount");

  const urdf::Link& palm_urdf = reader.Link(kPalmLink, "hand");
  if (!palm_urdf.parent_joint) reader.Fail("link 'palm' has no parent joint");
  const urdf::Joint& palm_joint = *palm_urdf.parent_joint;
  reader.RequireFixed(palm_joint, "palm joint");
  reader.RequireParentChild(palm_joint, "palm joint", kHandMountLink, kPalmLink);
  RigidLink palm = reader.Body(kPalmLink, "hand");

  std::vector<Finger> fingers = ReadFingers(reader, urdf_xml);
  reader.RequireAllLinksUsed();

  HandModel hand(source, std::move(mount_link), std::move(palm),
                 ToIsometry(palm_joint.parent_to_joint_origin_transform), std::move(fingers));
  return RobotModel{source,
                    std::move(arm),
                    X_FH,
                    std::move(hand),
                    model->getName(),
                    Eigen::Isometry3d::Identity(),
                    {}};
}

RobotModel LoadRobotModel(const std::filesystem::path& path) {
  return ParseRobotModel(ReadInputFile(path, input_kind::kRobot), path.string());
}

std::filesystem::path DefaultRobotDescriptionPath() {
  return DataDirectory() / kShippedRelativePath;
}

}  // namespace graspsynth
