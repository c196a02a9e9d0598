#pragma once

/// @file
/// Hand-made demonstration trials with known pre-grasp and grasp samples, for the tests of
/// learning_data/ and solver/.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "learning_data/demo_log.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth::testing {

/// The object centre at rest of the shipped scene, world, m.
inline Eigen::Vector3d SceneObjectCentre() { return {-0.25, 0.85, 0.025}; }

/// (d cos eta, d sin eta): an object-centred table-plane position from polar form (m, deg).
inline Eigen::Vector2d Polar(double d, double eta_deg) {
  const double eta = eta_deg * M_PI / 180.0;
  return {d * std::cos(eta), d * std::sin(eta)};
}

/// How MakeTrial builds a trial: the wrist approaches radially from outside, reaches
/// `pregrasp_xy` (object-centred) at sample `approach_samples`, moves in a straight line to
/// `grasp_xy` over `grasp_samples` samples (the last one is the grasp event), then lifts.
struct TrialSpec {
  double theta_deg = 60.0;
  Eigen::Vector3d p_WO = SceneObjectCentre();
  Eigen::Vector2d pregrasp_xy = Polar(0.4099999, -52.4);  ///< just inside a 0.41 m cylinder
  Eigen::Vector2d grasp_xy = Polar(0.345, -63.1);
  double wrist_dz = 0.07;    ///< wrist height above the object centre during the approach, m
  int approach_samples = 5;  ///< samples before the pre-grasp, each 5 cm further out
  int grasp_samples = 6;     ///< pre-grasp .. grasp, inclusive
  int lift_samples = 5;      ///< after the grasp; the last one is the end event
  double lift = 0.10;        ///< object rise at the end, m
  double dt = 1.0 / 30.0;    ///< s
  double t0 = 0.5;           ///< time of the first sample, s
  std::string trial = "1";
};

/// A log following `spec`. Sample `spec.approach_samples` is the pre-grasp sample and sample
/// `spec.approach_samples + spec.grasp_samples - 1` the grasp sample.
inline DemoLog MakeTrial(const TrialSpec& spec) {
  DemoLog log;
  log.source = "trial_" + spec.trial + ".csv";
  log.metadata.theta_deg = spec.theta_deg;
  log.metadata.object_position = spec.p_WO;
  log.metadata.trial = spec.trial;
  log.metadata.operator_name = "test";
  log.metadata.sample_rate_hz = 1.0 / spec.dt;

  const Eigen::Quaterniond q_grasp = Eigen::Quaterniond(
      Eigen::AngleAxisd(spec.theta_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  const Eigen::Vector2d out = spec.pregrasp_xy.normalized();
  double t = spec.t0;
  const auto add = [&](const Eigen::Vector2d& xy, double dz, double object_rise, double closure,
                       DemoEvent event) {
    DemoSample s;
    s.t = t;
    t += spec.dt;
    s.p_WH = spec.p_WO + Eigen::Vector3d(xy.x(), xy.y(), dz);
    s.q_WH = q_grasp;
    s.f = HandVector::Constant(closure);
    s.event = event;
    s.p_WO = spec.p_WO + Eigen::Vector3d(0.0, 0.0, object_rise);
    log.samples.push_back(s);
  };
  for (int k = spec.approach_samples; k >= 1; --k) {
    add(spec.pregrasp_xy + 0.05 * k * out, spec.wrist_dz, 0.0, 0.0, DemoEvent::kNone);
  }
  for (int k = 0; k < spec.grasp_samples; ++k) {
    const double s = spec.grasp_samples == 1 ? 1.0 : double(k) / (spec.grasp_samples - 1);
    const bool last = k + 1 == spec.grasp_samples;
    add((1.0 - s) * spec.pregrasp_xy + s * spec.grasp_xy, spec.wrist_dz, 0.0, 0.8 * s,
        last ? DemoEvent::kGrasp : DemoEvent::kNone);
  }
  for (int k = 1; k <= spec.lift_samples; ++k) {
    const double rise = spec.lift * k / spec.lift_samples;
    add(spec.grasp_xy, spec.wrist_dz + rise, rise, 0.8,
        k == spec.lift_samples ? DemoEvent::kEnd : DemoEvent::kNone);
  }
  return log;
}

}  // namespace graspsynth::testing
