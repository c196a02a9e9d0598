#include "solver/line_principle.hpp"

#include <algorithm>
#include <cmath>

#include "common/demand.hpp"
#include "motion/resample.hpp"
#include "solver/bracket.hpp"

namespace graspsynth {

namespace {

double Wrap(double a) { return std::remainder(a, 2.0 * M_PI); }

// The "palm down, long axis z_H along world x" orientation: x_H = -z_W, y_H = y_W, z_H = x_W.
Eigen::Matrix3d CanonicalHand() {
  Eigen::Matrix3d R;
  R.col(0) = -Eigen::Vector3d::UnitZ();
  R.col(1) = Eigen::Vector3d::UnitY();
  R.col(2) = Eigen::Vector3d::UnitX();
  return R;
}

Eigen::Matrix3d Rz(double yaw) { return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).matrix(); }

// Yaw of the hand's long axis z_H projected on the table, rad.
double HandYaw(const Eigen::Matrix3d& R) { return std::atan2(R(1, 2), R(0, 2)); }

Eigen::Vector3d RotationVector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d FromRotationVector(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, r / angle).matrix();
}

// The world yaw of the grip axis, `along` in the object frame, of the object at pose X_WO.
double HandleAngle(const Eigen::Isometry3d& X_WO, const Eigen::Vector3d& along) {
  const Eigen::Vector3d h = X_WO.linear() * along;
  return std::atan2(h.y(), h.x());
}

double HandleAngle(const SceneModel& scene, double theta) {
  const Eigen::Vector3d h = scene.object.HandleDirection(scene.ObjectPose(theta));
  return std::atan2(h.y(), h.x());
}

LinearFit FitLinear(const std::vector<double>& x, const std::vector<double>& y) {
  LinearFit fit;
  const int n = static_cast<int>(x.size());
  if (n == 0) return fit;
  double mx = 0.0, my = 0.0;
  for (int i = 0; i < n; ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxx = 0.0, sxy = 0.0;
  for (int i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  fit.b = sxx > 1e-12 ? sxy / sxx : 0.0;
  fit.a = my - fit.b * mx;
  return fit;
}

}  // namespace

bool LinePrincipleOptions::IsValid(std::string* why) const {
  if (!(std::isfinite(min_score) && min_score >= 0.0 && min_score <= 1.0)) {
    if (why) *why = "min_score must be in [0, 1]";
    return false;
  }
  if (!line.IsValid(why)) return false;
  if (waypoints < 2) {
    if (why) *why = "waypoints must be >= 2";
    return false;
  }
  if (!(std::isfinite(side_dead_band) && side_dead_band >= 0.0)) {
    if (why) *why = "side_dead_band must be >= 0 (m)";
    return false;
  }
  return true;
}

SideKnot SideModel::At(double theta) const {
  GS_DEMAND(!knots.empty(), "the line principle's side has no grasps");
  if (theta <= knots.front().theta) return knots.front();
  if (theta >= knots.back().theta) return knots.back();
  size_t i = 1;
  while (knots[i].theta < theta) ++i;
  const SideKnot& a = knots[i - 1];
  const SideKnot& b = knots[i];
  const double u = (theta - a.theta) / (b.theta - a.theta);
  auto mix = [u](const auto& x, const auto& y) { return (1.0 - u) * x + u * y; };
  SideKnot k;
  k.theta = theta;
  k.height = mix(a.height, b.height);
  k.yaw = mix(a.yaw, b.yaw);
  k.residual = mix(a.residual, b.residual);
  k.fingers = mix(a.fingers, b.fingers);
  k.duration = mix(a.duration, b.duration);
  k.approach.resize(a.approach.size());
  for (size_t j = 0; j < a.approach.size(); ++j) {
    RelativeWaypoint& w = k.approach[j];
    w.u = a.approach[j].u;
    w.p = mix(a.approach[j].p, b.approach[j].p);
    w.r = mix(a.approach[j].r, b.approach[j].r);
    w.df = mix(a.approach[j].df, b.approach[j].df);
  }
  return k;
}

namespace {

// The placement of entry `e` at orientation theta (rad): at its own motion's object centre, or
// at the scene's when it stands there up to rounding (a log records the centre as it computed
// it, e.g. 0.8499999999999999 for 0.85: the fixed-position study keeps the scene's exact pose).
Placement OwnPlacement(const SceneModel& scene, const LibraryEntry& e, double theta) {
  const Eigen::Vector2d xy = e.motion.p_WO.head<2>();
  if ((xy - scene.object_centre_xy).norm() < 1e-9) return {theta, std::nullopt};
  return {theta, xy};
}

// The knot of a library grasping motion at object orientation theta (rad, object pose X_WO)
// on `side`, its approach resampled to n waypoints; the handle axis point under the hand in H,
// weighted by `weight`, added to *handle_in_hand.
SideKnot KnotOf(const SceneModel& scene, const GraspingMotion& motion,
                const Eigen::Isometry3d& X_WO, double theta, int side, int n, double weight,
                Eigen::Vector3d* handle_in_hand) {
  const MotionWaypoint& g = motion.grasp();
  const Eigen::Matrix3d R_G = g.q_WH.toRotationMatrix();
  const double yaw = HandYaw(R_G);
  SideKnot knot;
  knot.theta = theta;
  knot.height = g.p_WH.z() - X_WO.translation().z();
  // unwrap about the side's nominal yaw (+-90 deg: z_H across the handle).
  const double rel = Wrap(yaw - HandleAngle(scene, theta));
  knot.yaw = side * M_PI / 2 + Wrap(rel - side * M_PI / 2);
  knot.residual = RotationVector((Rz(yaw) * CanonicalHand()).transpose() * R_G);
  knot.fingers = g.f;
  // the handle axis point under the hand: where the hand's forward axis (z_H, seen from
  // above) crosses the handle's axis - the bar in the pinch of the scripted grasp and in the
  // hook of the synthetic operator alike, whatever the hand's yaw; the point nearest the
  // wrist when the hand lies (nearly) along the handle. In H.
  const ObjectModel& o = scene.object;
  const HandleAxis& handle = o.Handle("the line principle");
  const Eigen::Vector3d h = o.HandleDirection(X_WO);
  const Eigen::Vector3d a0 =
      X_WO.translation() + (handle.axis_height - o.rest_height) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector2d u = R_G.col(2).head<2>().normalized();
  const Eigen::Vector2d d = (a0 - g.p_WH).head<2>();
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  const double sine = cross(u, h.head<2>());
  const double crossing = std::abs(sine) > 0.1 ? -cross(u, d) / sine : (g.p_WH - a0).dot(h);
  const double along = std::clamp(crossing, handle.start_radius, handle.end_radius);
  *handle_in_hand += weight * (R_G.transpose() * (a0 + along * h - g.p_WH));
  // the approach relative to the grasp.
  const GraspingMotion r = Resample(motion, n);
  knot.duration = r.duration();
  const Eigen::Matrix3d Ryaw = Rz(-yaw);
  for (int i = 0; i < n; ++i) {
    const MotionWaypoint& w = r.waypoints[i];
    RelativeWaypoint a;
    a.u = static_cast<double>(i) / (n - 1);
    a.p = Ryaw * (w.p_WH - g.p_WH);
    a.r = RotationVector(R_G.transpose() * w.q_WH.toRotationMatrix());
    a.df = w.f - g.f;
    knot.approach.push_back(a);
  }
  return knot;
}

}  // namespace

int GraspSide(const SceneModel& scene, const LibraryEntry& e, double dead_band) {
  const double th = e.theta_deg * kDeg;
  const MotionWaypoint& g = e.motion.grasp();
  const double rel = Wrap(HandYaw(g.q_WH.toRotationMatrix()) - HandleAngle(scene, th));
  const int side = HandleSide(scene, OwnPlacement(scene, e, th), g.p_WH, dead_band);
  if (side != 0) return side;
  return rel > 0.0 ? 1 : -1;
}

LinePrincipleModel FitLinePrinciple(const GraspLibrary& library, const SceneModel& scene,
                                    const LinePrincipleOptions& options) {
  LinePrincipleModel model;
  if (scene.object.handle) model.handle_along = scene.object.handle->Along();
  const auto& entries = library.entries;
  if (entries.size() < 2) {
    model.message = "the line principle needs at least two library entries";
    return model;
  }
  for (const LibraryEntry& e : entries) {
    model.entry_sides.push_back(GraspSide(scene, e, options.side_dead_band));
  }
  // the entries the models are fitted over: the robust ones when two or more are.
  std::vector<size_t> used;
  for (size_t k = 0; k < entries.size(); ++k) {
    if (entries[k].score >= options.min_score) used.push_back(k);
  }
  if (used.size() < 2) {
    used.clear();
    for (size_t k = 0; k < entries.size(); ++k) used.push_back(k);
  }
  model.fitted_entries = static_cast<int>(used.size());
  std::vector<double> theta;
  std::vector<Eigen::Vector2d> points;
  for (size_t k : used) {
    const LibraryEntry& e = entries[k];
    const Eigen::Isometry3d X_WO = scene.ObjectPose(OwnPlacement(scene, e, e.theta_deg * kDeg));
    theta.push_back(e.theta_deg * kDeg);
    points.push_back((e.motion.grasp().p_WH - X_WO.translation()).head<2>());
  }
  model.theta_min = entries.front().theta_deg * kDeg;
  model.theta_max = entries.back().theta_deg * kDeg;
  model.wrist_line = FitWristLine(points, options.line);
  if (!model.wrist_line.usable()) {
    model.message = "the wrist line could not be fitted: " + model.wrist_line.message;
    return model;
  }
  const Line2d& line = model.wrist_line.line;
  std::vector<double> s;
  const int n = options.waypoints;
  const double inv = 1.0 / static_cast<double>(used.size());
  for (int si = 0; si < 2; ++si) model.sides[si].side = si == 1 ? 1 : -1;
  for (size_t k = 0; k < used.size(); ++k) {
    const LibraryEntry& e = entries[used[k]];
    const Eigen::Isometry3d X_WO = scene.ObjectPose(OwnPlacement(scene, e, theta[k]));
    s.push_back(line.direction.dot(points[k] - line.point));
    const int side = model.entry_sides[used[k]];
    const SideKnot knot =
        KnotOf(scene, e.motion, X_WO, theta[k], side, n, inv, &model.handle_in_hand);
    model.sides[side > 0 ? 1 : 0].knots.push_back(knot);  // used[] is theta-increasing
  }
  model.s = FitLinear(theta, s);
  for (int si = 0; si < 2; ++si) {
    SideModel& m = model.sides[si];
    m.entries = static_cast<int>(m.knots.size());
    // this side's own position model.
    std::vector<Eigen::Vector2d> side_points;
    std::vector<double> side_theta;
    for (size_t k = 0; k < used.size(); ++k) {
      if ((model.entry_sides[used[k]] > 0 ? 1 : 0) != si) continue;
      side_points.push_back(points[k]);
      side_theta.push_back(theta[k]);
    }
    if (side_points.size() >= 2) {
      const WristLineResult fit = FitWristLine(side_points, options.line);
      if (fit.usable()) {
        m.has_line = true;
        m.line = fit.line;
        std::vector<double> side_s;
        for (const Eigen::Vector2d& p : side_points) {
          side_s.push_back(m.line.direction.dot(p - m.line.point));
        }
        m.s = FitLinear(side_theta, side_s);
      }
    }
  }
  model.valid = true;
  return model;
}

namespace {

// The grasp of `side` at theta relative to the handle, from the side's own grasps, or, where
// that side was not demonstrated, from the other side's, to be turned by *turn = 180 deg.
SideKnot KnotAt(const LinePrincipleModel& model, double theta, int side, double* turn) {
  const SideModel& own = model.side_model(side);
  *turn = own.entries == 0 ? M_PI : 0.0;
  return (own.entries == 0 ? model.side_model(-side) : own).At(theta);
}

// The grasp wrist pose of `side` at the placement's theta, the object at X_WO, for its knot `k`
// (KnotAt): the wrist on the side's line, the rest from the knot.
Eigen::Isometry3d GraspPose(const LinePrincipleModel& model, double theta,
                            const Eigen::Isometry3d& X_WO, int side, const SideKnot& k,
                            double turn) {
  const SideModel& own = model.side_model(side);
  const Line2d& line = own.has_line ? own.line : model.wrist_line.line;
  const double s = own.has_line ? own.s(theta) : model.s(theta);
  const Eigen::Vector2d p_xy = line.point + s * line.direction;
  const double yaw = HandleAngle(X_WO, model.handle_along) + k.yaw + turn;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Rz(yaw) * CanonicalHand() * FromRotationVector(k.residual);
  X.translation() = X_WO.translation() + Eigen::Vector3d(p_xy.x(), p_xy.y(), k.height);
  return X;
}

}  // namespace

Eigen::Isometry3d LinePrincipleGraspPose(const LinePrincipleModel& model,
                                         const Placement& placement, const Eigen::Isometry3d& X_WO,
                                         int side) {
  double turn = 0.0;
  const SideKnot k = KnotAt(model, placement.theta, side, &turn);
  return GraspPose(model, placement.theta, X_WO, side, k, turn);
}

GraspingMotion LinePrincipleMotion(const LinePrincipleModel& model, const Placement& placement,
                                   const Eigen::Isometry3d& X_WO, int side) {
  const double theta = placement.theta;
  double turn = 0.0;
  const SideKnot k = KnotAt(model, theta, side, &turn);
  const Eigen::Isometry3d X_G = GraspPose(model, theta, X_WO, side, k, turn);
  const Eigen::Matrix3d R_G = X_G.linear();
  const Eigen::Matrix3d Ryaw = Rz(HandYaw(R_G));
  GraspingMotion motion;
  motion.theta = theta;
  motion.p_WO = X_WO.translation();
  motion.source = "line principle";
  for (const RelativeWaypoint& a : k.approach) {
    MotionWaypoint w;
    w.t = a.u * k.duration;
    w.p_WH = X_G.translation() + Ryaw * a.p;
    w.q_WH = Eigen::Quaterniond(R_G * FromRotationVector(a.r)).normalized();
    w.f = k.fingers + a.df;
    motion.waypoints.push_back(w);
  }
  // the last waypoint is the modelled grasp exactly.
  motion.waypoints.back().p_WH = X_G.translation();
  motion.waypoints.back().q_WH = Eigen::Quaterniond(R_G).normalized();
  motion.waypoints.back().f = k.fingers;
  return motion;
}

}  // namespace graspsynth
