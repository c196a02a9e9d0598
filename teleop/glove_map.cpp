#include "teleop/glove_map.hpp"

#include <algorithm>
#include <cmath>

namespace graspsynth::teleop {
namespace {

constexpr double kSpread = Radians(15.0);  // finger spread at full abduction reading
constexpr int kThumbOpposition = 0;        // f0, derived
constexpr int kMiddleAbduction = 7;        // f7, derived

}  // namespace

GloveMap GloveMap::Default(const HandModel& hand) {
  GloveMap map;
  const auto flex = [&](int f, int sensor) {
    map.joints[f] = {sensor, std::max(0.0, hand.lower()[f]), hand.upper()[f]};
  };
  // thumb: f1 ab/adduction over its range, f2 MCP and f3 IP flexion.
  map.joints[1] = {kThumbIndex, hand.lower()[1], hand.upper()[1]};
  flex(2, kThumbNear);
  flex(3, kThumbFar);
  // fingers: MCP and PIP flexion.
  flex(5, kIndexNear);
  flex(6, kIndexFar);
  flex(8, kMiddleNear);
  flex(9, kMiddleFar);
  flex(11, kRingNear);
  flex(12, kRingFar);
  flex(14, kLittleNear);
  flex(15, kLittleFar);
  // abduction: positive j1 turns a finger toward the little finger's side, so the index spreads
  // with negative values and the ring and little fingers with positive ones.
  map.joints[4] = {kIndexMiddle, 0.0, -kSpread};
  map.joints[10] = {kMiddleRing, 0.0, kSpread};
  map.joints[13] = {kRingLittle, 0.0, kSpread};
  map.joints[kThumbOpposition] = {-1, hand.lower()[0], hand.upper()[0]};
  map.joints[kMiddleAbduction] = {-1, 0.0, 0.0};
  return map;
}

HandVector GloveToJoints(const GloveMap& map, const HandModel& hand,
                         const Eigen::Ref<const Eigen::Matrix<double, 14, 1>>& g_raw) {
  const Eigen::Matrix<double, 14, 1> g = g_raw.cwiseMax(0.0).cwiseMin(1.0);
  HandVector f;
  for (int k = 0; k < kHandDof; ++k) {
    const GloveJointMap& m = map.joints[k];
    double u = 0.0;
    if (m.sensor >= 0) {
      u = g[m.sensor];
    } else if (k == kThumbOpposition) {
      // a thumb brought toward the index and flexed is an opposed thumb.
      u = 0.5 * ((1.0 - g[kThumbIndex]) + g[kThumbNear]);
    }
    f[k] = std::clamp(m.at_zero + (m.at_one - m.at_zero) * u, hand.lower()[k], hand.upper()[k]);
  }
  return f;
}

}  // namespace graspsynth::teleop
