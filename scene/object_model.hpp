#pragma once

/// @file
/// An object to grasp, as a file describes it (format graspsynth-object/1, models/README.md,
/// "Objects"): one rigid body made of parts - boxes, cylinders, capsules, spheres and closed
/// triangle meshes - each with its pose in the object frame, its mass (or density) and its
/// friction with the fingers. Every module (collision, simulation, grasp quality, viewer)
/// builds the object from this one description.
///
/// The object frame O: origin at the object centre, z up. The object rests upright on the
/// table on the lowest point of its parts that touch the table, so that O stands rest_height
/// above the table top. Where the object stands on the table and how it is turned at
/// orientation theta is the scene's (scene/scene_model.hpp).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/arm_model.hpp"

namespace graspsynth {

/// What a part of an object touches in the simulation. A part that touches only the table is
/// a support: it carries no mass and meets only the table (the pan stands on two boxes
/// inscribed in its cylinder, because ODE's cylinder-box contact rocks).
enum class PartContact { kRobotAndTable, kRobot, kTable };

/// One part of an object.
struct ObjectPart {
  std::string name;
  /// Geometry and pose in the object frame O (CollisionShape::X_LG is X_OP).
  CollisionShape shape;
  double mass = 0.0;      ///< kg; 0 for a support part
  double friction = 1.0;  ///< Coulomb coefficient with the fingers
  PartContact touches = PartContact::kRobotAndTable;

  /// Whether the robot can touch the part: every part but a support. The collision scene, the
  /// viewer and the figure hold these parts only.
  bool touches_robot() const { return touches != PartContact::kTable; }
};

/// The grip axis, for objects grasped across a line: a handle's bar, or a line through the
/// body of an object held by it (a box pinched across its thickness). A horizontal segment
/// along `direction` in the object's xy plane, from start_radius to end_radius from the object
/// centre along it (negative behind the centre), axis_height above the table when the object
/// rests. The hand closes across it: the grip placement of the synthetic operator, the line
/// principle and the refinement aim at it.
struct HandleAxis {
  double start_radius = 0.0;  ///< m from the object centre along the axis
  double end_radius = 0.0;    ///< m from the object centre along the axis
  double axis_height = 0.0;   ///< m above the table
  double direction = 0.0;     ///< rad from the object's x axis about z; 0 for the pan's handle

  /// The unit vector along the axis, in the object frame.
  Eigen::Vector3d Along() const {
    return Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0);
  }
};

/// Mass properties of an object.
struct ObjectInertia {
  double mass = 0.0;                               ///< kg
  Eigen::Vector3d p_OC = Eigen::Vector3d::Zero();  ///< centre of mass in the object frame O, m
  Eigen::Matrix3d I_C = Eigen::Matrix3d::Zero();   ///< about the centre of mass, O axes, kg m^2
};

/// An object to grasp: its parts, how it rests, and its handle if it has one.
struct ObjectModel {
  std::string name;
  std::string source;  ///< the file it came from, for messages
  std::vector<ObjectPart> parts;
  /// Coulomb coefficient with the fingers of the parts that state none.
  double friction = 1.0;
  /// Height of the object frame above the table top when the object rests on it, m (the
  /// depth of the lowest point of the parts that touch the table below O).
  double rest_height = 0.0;
  std::optional<HandleAxis> handle;
  /// The object stands for the paper's pan (`"paper_object": true`): studies of it compare
  /// their Table I with the paper's and check the paper's grasp wrist poses. Other objects
  /// have no published table; their studies report their own.
  bool paper_object = false;

  /// The handle's axis. Throws InputError naming the object when it has none; `needed_by`
  /// says what needed it.
  const HandleAxis& Handle(std::string_view needed_by) const;
  /// Mass, centre of mass and inertia from the parts (uniform density within each part).
  ObjectInertia Inertia() const;
  /// The grip axis's direction in the world for the object at pose X_WO: the object's x axis
  /// for an object without one.
  Eigen::Vector3d HandleDirection(const Eigen::Isometry3d& X_WO) const;
};

/// Parses an object description (format graspsynth-object/1). `source` names it in messages;
/// mesh files are found relative to `mesh_dir` (the object file's folder). Throws InputError
/// naming the source, the field and the value (or the mesh file and its fault).
ObjectModel ParseObjectModel(std::string_view json_text, const std::string& source,
                             const std::filesystem::path& mesh_dir);

/// Reads and parses an object file. Throws InputError naming the file.
ObjectModel LoadObjectModel(const std::filesystem::path& path);

/// The folder of the shipped object descriptions (models/objects under the data directory).
std::filesystem::path DefaultObjectDirectory();

/// An object named by `name_or_file`: a path to a file if it names an existing file or ends
/// in ".json", otherwise the shipped object of that name (models/objects/<name>.json).
/// Throws InputError naming the object and, for an unknown name, the shipped ones.
std::filesystem::path ResolveObjectPath(const std::string& name_or_file);

/// The lowest point of `shape` at its pose (X_LG), along z, in the shape's link frame.
double LowestPoint(const CollisionShape& shape);

/// Volume of a primitive or mesh shape, m^3.
double ShapeVolume(const CollisionShape& shape);

}  // namespace graspsynth
