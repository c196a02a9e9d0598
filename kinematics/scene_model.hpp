#pragma once

/// @file
/// The immutable description of the robot's surroundings: the table, the pan-like object of
/// DESIGN.md and the grasp workspace region, loaded from models/scene.json.
///
/// The object frame O has its origin at the object centre (the centre of the pan's body), z up
/// and x along the handle. At orientation theta the object stands at its fixed centre, turned
/// about the vertical so that the handle points along phi(theta) = theta + handle_offset in the
/// world.

#include <filesystem>
#include <string>
#include <string_view>

#include "kinematics/arm_model.hpp"
#include "kinematics/types.hpp"

namespace graspsynth {

/// The table: a box whose top face is the plane z = top_z.
struct TableModel {
  double top_z = 0.0;                                   ///< m, world
  Eigen::Vector2d centre_xy = Eigen::Vector2d::Zero();  ///< m, world
  Eigen::Vector3d size = Eigen::Vector3d::Zero();       ///< full side lengths, m
  double friction = 0.8;                                ///< Coulomb coefficient with the object
};

/// The pan: a short cylinder (the body) with a radial bar handle (a box).
struct ObjectModel {
  std::string name;
  Eigen::Vector2d centre_xy = Eigen::Vector2d::Zero();  ///< object centre in the table plane, m
  double handle_offset = 0.0;        ///< rad; the handle points along theta + handle_offset
  double body_radius = 0.0;          ///< m
  double body_height = 0.0;          ///< m
  double handle_start_radius = 0.0;  ///< m from the centre
  double handle_end_radius = 0.0;    ///< m from the centre
  double handle_width = 0.0;         ///< horizontal side of the bar's cross-section, m
  double handle_thickness = 0.0;     ///< vertical side of the bar's cross-section, m
  double handle_axis_height = 0.0;   ///< height of the bar's axis above the table, m
  double body_mass = 0.0;            ///< kg
  double handle_mass = 0.0;          ///< kg
  double friction = 1.0;             ///< Coulomb coefficient with the fingers

  /// Height of the object centre above the table when the pan rests on it.
  double rest_height() const { return 0.5 * body_height; }

  /// The pan's body in the object frame O: a cylinder of body_radius and body_height centred
  /// at O, axis z. Every module that builds the pan (collision, simulation, viewer) uses it.
  CollisionShape BodyShape() const;
  /// The handle in O: a box from handle_start_radius to handle_end_radius along x,
  /// handle_width across and handle_thickness high, its axis handle_axis_height above the
  /// table.
  CollisionShape HandleShape() const;
};

/// Where the grasping motion starts: the pre-grasp pose is the first wrist sample inside it.
struct GraspRegionModel {
  enum class Shape { kCylinder, kSphere };
  Shape shape = Shape::kCylinder;
  double radius = 0.41;  ///< m, around the object centre
  double height = 1.0;   ///< cylinder: full height, centred on the object centre, m
};

/// Where the object stands on the table: its orientation theta about the vertical (rad), at
/// the scene's object centre. The one value a task carries down to every stage; a position on
/// the table would be a further field here, read by SceneModel::ObjectPose alone.
struct Placement {
  double theta = 0.0;  ///< rad
};

/// Table, object and grasp region.
struct SceneModel {
  std::string source;
  TableModel table;
  ObjectModel object;
  GraspRegionModel grasp_region;

  /// Pose X_WO of the object frame at rest on the table at orientation theta (radians).
  Eigen::Isometry3d ObjectPose(double theta) const;
  /// Pose X_WO of the object frame at rest on the table at `placement`.
  Eigen::Isometry3d ObjectPose(const Placement& placement) const {
    return ObjectPose(placement.theta);
  }
};

/// Parses a scene description (format graspsynth-scene/1). `source` names it in messages.
/// Throws InputError naming the source, the field and the value for anything missing, of the
/// wrong type, non-finite or out of range.
SceneModel ParseSceneModel(std::string_view json_text, const std::string& source);

/// Reads and parses a scene file. Throws InputError naming the file.
SceneModel LoadSceneModel(const std::filesystem::path& path);

/// models/scene.json under $GRASPSYNTH_DATA_DIR if set, else in this source checkout.
std::filesystem::path DefaultSceneModelPath();

}  // namespace graspsynth
