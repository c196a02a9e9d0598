#pragma once

/// @file
/// What the browser viewer (viewer/, served by viewer/viewer_server.hpp) draws: the scene
/// document, sent once, and the frames, sent at the control rate.
///
/// The scene document (`graspsynth-viewer-scene/1`, JSON) lists every body with its primitive
/// shapes in the body's own frame, and the start camera:
///
///     {"format": "graspsynth-viewer-scene/1",
///      "robot": "models/pa10_gifu3.urdf", "scene": "models/scene.json",   (their sources)
///      "links": [{"name": "base_link", "group": "arm",
///                 "shapes": [{"kind": "cylinder", "radius": r, "length": L,
///                             "pose": [x, y, z, qw, qx, qy, qz]}, ...]}, ...],
///      "object": {"name": "pan", "group": "object", "shapes": [...]},
///      "table": {"name": "table", "group": "table", "pose": [...], "shapes": [...]},
///      "grasp_region": {"shape": "cylinder", "centre": [x, y, z], "radius": r, "height": h},
///      "camera": {"eye": [x, y, z], "target": [x, y, z], "up": [0, 0, 1], "fov_deg": 45}}
///
/// Shapes: `box` with `size` (full sides x, y, z); `capsule` and `cylinder` with `radius` and
/// `length` (straight part along the shape's z axis; a capsule adds hemispherical caps beyond
/// it); `sphere` with `radius`. Metres; poses are [x, y, z, qw, qx, qy, qz] (unit quaternion, w
/// first), the shape in its body's frame. "links" are the robot's bodies in the order of
/// ViewerLinkPoses: the arm's base_link and S1_link .. W2_link (8), the hand mount, the palm,
/// then every finger's links in the hand's order (the Gifu: link1 .. link4 of thumb, index,
/// middle, ring, little, 20): ViewerLinkCount(robot) in all. A
/// body without geometry (a finger knuckle) has no shapes but keeps its place. The table is
/// static (its pose is in world); the object's pose comes with every frame.
///
/// A frame (ViewerFrameJson) is one compact line of JSON:
///
///     {"t": 1.25, "links": [[x, y, z, qw, qx, qy, qz], ...], "object": [...], "text": "...",
///      "contacts": [[x, y, z], ...], "outcome": {"success": false, "text": "..."}}
///
/// with the world pose X_WL of every link in the scene's order, the object's X_WO, the time (s)
/// and a status line for the operator; a replay of a simulated trial adds the object-hand
/// contact points (world, m; the key only when there are some) and, once the trial's outcome is
/// decided, the outcome (the key only then). The live teleoperation view sends neither.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/arm_model.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/types.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::viewer {

/// The `format` value of the scene document.
inline constexpr std::string_view kViewerSceneFormat = "graspsynth-viewer-scene/1";

/// Number of robot bodies in the scene and in every frame: 8 arm, mount, palm, then every
/// phalanx of `robot`'s hand (20 for the Gifu: 30 in all).
int ViewerLinkCount(const RobotModel& robot);

/// The start view of the page (the user may orbit from there).
struct ViewerCamera {
  Eigen::Vector3d eye = Eigen::Vector3d(2.0, -1.0, 1.2);    ///< camera position, world, m
  Eigen::Vector3d target = Eigen::Vector3d(0.0, 0.4, 0.4);  ///< point looked at, world, m
  double fov_deg = 45.0;                                    ///< vertical field of view, deg
};

/// A view of the whole workcell: the target a little past the middle of the arm base and the
/// object, 0.3 m above the table; the eye 2.6 m from it, 30 deg above the horizontal, to the
/// right of the base-to-object line and swung 35 deg toward the object, so that the arm is seen
/// from the side and the pan and the table in front of it.
ViewerCamera DefaultViewerCamera(const SceneModel& scene);

/// Parses a camera placement "EX,EY,EZ" or "EX,EY,EZ,TX,TY,TZ" (metres, world; blanks allowed
/// after commas). The target, when not given, is `defaults`' target. Throws InputError naming
/// the value when a field is not a finite number, the count is neither 3 nor 6, or the eye
/// equals the target.
ViewerCamera ParseViewerCamera(std::string_view text, const ViewerCamera& defaults);

/// One drawn body: a name, the colour group ("arm", "hand", "object", "table") and its shapes,
/// each with its pose in the body's frame.
struct ViewerBody {
  std::string name;
  std::string group;
  std::vector<CollisionShape> shapes;
};

/// The robot's bodies in the scene's order (see the file comment): ViewerLinkCount(robot) of them.
std::vector<ViewerBody> ViewerRobotBodies(const RobotModel& robot);

/// The pan in its frame O: the body cylinder and the handle bar (as the collision scene and
/// the simulation build it).
ViewerBody ViewerObjectBody(const ObjectModel& object);

/// The scene document (see the file comment), one JSON object.
std::string ViewerSceneJson(const RobotModel& robot, const SceneModel& scene,
                            const ViewerCamera& camera);

/// World poses X_WL of the robot's bodies in the scene's order at arm joints q (rad) and
/// actuated hand joints f (rad, f0..f15): the arm's link frames (ArmLinkFrames), then
/// X_WH = X_WF * X_FH for the mount, X_WH * X_HP for the palm and X_WH * X_HL for each
/// phalanx (HandLinkFrames). ViewerLinkCount(robot) poses.
std::vector<Eigen::Isometry3d> ViewerLinkPoses(const RobotModel& robot,
                                               const Eigen::Ref<const Vector7d>& q,
                                               const Eigen::Ref<const HandVector>& f);

/// A trial's outcome as a frame shows it (a banner on the page).
struct ViewerOutcome {
  bool success = false;
  std::string text;  ///< e.g. "success: lifted 120.5 mm ..." or "FAILED (dropped): ..."
};

/// What one frame shows.
struct ViewerState {
  double t = 0.0;                                          ///< s (replay or session time)
  Vector7d arm = Vector7d::Zero();                         ///< arm joints, rad
  HandVector hand = HandVector::Zero();                    ///< actuated hand joints, rad
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  ///< object pose, world
  std::string text;                                        ///< status line for the operator
  std::vector<Eigen::Vector3d> contacts;  ///< object-hand contact points, world, m (physics)
  std::optional<ViewerOutcome> outcome;   ///< the trial's outcome, once decided (physics)
};

/// The frame of `state` (see the file comment): positions rounded to 1e-6 m, quaternions to
/// 1e-6 and sign-normalized (w >= 0), the text JSON-escaped (invalid UTF-8 is replaced).
std::string ViewerFrameJson(const RobotModel& robot, const ViewerState& state);

}  // namespace graspsynth::viewer
