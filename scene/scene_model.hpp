#pragma once

/// @file
/// The immutable description of the robot's surroundings: the table, the object (a file of its
/// own, scene/object_model.hpp: the pan of DESIGN.md by default) and where it stands, and
/// the grasp workspace region, loaded from models/scene.json.
///
/// The object frame O has its origin at the object centre, z up (for the pan: x along the
/// handle). At orientation theta the object stands at the scene's object centre, resting on the
/// table, turned about the vertical so that its x axis points along
/// phi(theta) = theta + object_yaw_offset in the world.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "kinematics/arm_model.hpp"
#include "kinematics/types.hpp"
#include "scene/object_model.hpp"

namespace graspsynth {

/// The table: a box whose top face is the plane z = top_z.
struct TableModel {
  double top_z = 0.0;                                   ///< m, world
  Eigen::Vector2d centre_xy = Eigen::Vector2d::Zero();  ///< m, world
  Eigen::Vector3d size = Eigen::Vector3d::Zero();       ///< full side lengths, m
  double friction = 0.8;                                ///< Coulomb coefficient with the object
};

/// Where the grasping motion starts: the pre-grasp pose is the first wrist sample inside it.
struct GraspRegionModel {
  enum class Shape { kCylinder, kSphere };
  Shape shape = Shape::kCylinder;
  double radius = 0.41;  ///< m, around the object centre
  double height = 1.0;   ///< cylinder: full height, centred on the object centre, m
};

/// Where the object stands on the table: its orientation theta about the vertical (rad) and,
/// optionally, its centre in the table plane. The one value a task carries down to every
/// stage; SceneModel::ObjectPose turns it into the object's pose.
struct Placement {
  double theta = 0.0;  ///< rad
  /// The object centre in the table plane, world, m; empty: the scene's object centre (the
  /// paper's fixed position).
  std::optional<Eigen::Vector2d> xy;
};

/// Table, object and grasp region.
struct SceneModel {
  std::string source;
  TableModel table;
  ObjectModel object;
  /// Where the object stands: its centre in the table plane, world, m.
  Eigen::Vector2d object_centre_xy = Eigen::Vector2d::Zero();
  /// The object's yaw at orientation 0: its x axis points along theta + object_yaw_offset, rad.
  double object_yaw_offset = 0.0;
  GraspRegionModel grasp_region;
  /// Pose of the frame the scene's coordinates are in (S) in the study's world W: identity as
  /// read from a scene file; a robot's base frame once SceneInBaseFrame (scene/base_frame.hpp)
  /// has re-expressed it for a robot standing elsewhere.
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();

  /// Pose X_WO of the object frame at rest on the table at orientation theta (radians), at
  /// the scene's object centre.
  Eigen::Isometry3d ObjectPose(double theta) const { return ObjectPose(Placement{theta, {}}); }
  /// Pose X_WO of the object frame at rest on the table at `placement`.
  Eigen::Isometry3d ObjectPose(const Placement& placement) const;
  /// The object centre in the table plane at `placement`, world, m.
  Eigen::Vector2d CentreXY(const Placement& placement) const {
    return placement.xy.value_or(object_centre_xy);
  }
  /// Checks that `xy` (an object centre asked for: --at, a placement) is finite and on the
  /// table's top; throws InputError naming the position, the scene and the table's extent.
  void CheckOnTable(const Eigen::Vector2d& xy) const;
};

/// Parses a scene description. Format graspsynth-scene/2 names its object file
/// (`"object": "objects/pan.json"`, relative to `base_dir`, the scene file's folder);
/// graspsynth-scene/1, the format before objects were files, describes the pan inline and is
/// still read. A non-empty `object_override` (a shipped object's name or a file,
/// ResolveObjectPath) replaces the scene's object. `source` names the scene in messages.
/// Throws InputError naming the source, the field and the value for anything missing, of the
/// wrong type, non-finite or out of range, or the object file and its fault.
SceneModel ParseSceneModel(std::string_view json_text, const std::string& source,
                           const std::filesystem::path& base_dir = {},
                           const std::string& object_override = {});

/// Reads and parses a scene file, with its object (or `object_override`'s). Throws InputError
/// naming the file.
SceneModel LoadSceneModel(const std::filesystem::path& path,
                          const std::string& object_override = {});

/// The pan of graspsynth-scene/1, from the parameters that format gives inline: a cylinder
/// body of body_radius and body_height (touching only the robot) standing on two boxes
/// inscribed in it (touching only the table), and a box handle along x from
/// handle_start_radius to handle_end_radius, its axis handle_axis_height above the table.
/// models/objects/pan.json describes the same object.
struct LegacyPanParameters {
  double body_radius = 0.0, body_height = 0.0;
  double handle_start_radius = 0.0, handle_end_radius = 0.0;
  double handle_width = 0.0, handle_thickness = 0.0, handle_axis_height = 0.0;
  double body_mass = 0.0, handle_mass = 0.0, friction = 1.0;
};
ObjectModel LegacyPanObject(const std::string& name, const LegacyPanParameters& p,
                            const std::string& source);

/// models/scene.json under $GRASPSYNTH_DATA_DIR if set, else in this source checkout.
std::filesystem::path DefaultSceneModelPath();

}  // namespace graspsynth
