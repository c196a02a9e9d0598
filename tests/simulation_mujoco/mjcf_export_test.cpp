// The MJCF text: what it holds, and its options' checks.

#include "simulation_mujoco/mjcf_export.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using testing::ShippedSimulationModel;

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(MjcfExport, HasEveryJointAServoAndTheObject) {
  const SimulationModel& model = ShippedSimulationModel();
  const MjcfModel m = ExportMjcf(model, Placement{Radians(45.0), {}}, {});
  EXPECT_EQ(Count(m.xml, "type=\"hinge\""), kArmDof + model.robot().hand.joint_count());
  EXPECT_EQ(Count(m.xml, "<general "), kArmDof + model.robot().hand.joint_count());
  EXPECT_EQ(Count(m.xml, "<freejoint name=\"object\"/>"), 1);
  EXPECT_EQ(Count(m.xml, "<key "), 0);
  // every joint's force cap is its description's effort.
  EXPECT_NE(m.xml.find("forcerange=\"-200 200\""), std::string::npos);
  int object_geoms = 0;
  for (const MjcfGeom& g : m.geoms) object_geoms += g.role == MjcfRole::kObject;
  EXPECT_EQ(object_geoms, static_cast<int>(model.scene().object.parts.size()));
}

TEST(MjcfExport, ATrajectoryBecomesOneKeyframePerSample) {
  const MjcfModel m = ExportMjcf(ShippedSimulationModel(), ExampleTrajectory().placement(), {},
                                 &ExampleTrajectory());
  EXPECT_EQ(Count(m.xml, "<key "), static_cast<int>(ExampleTrajectory().samples.size()));
}

TEST(MjcfExport, ServoMappingsDifferInTheirGainOnly) {
  MjcfOptions soft;
  soft.servo = MujocoServo::kSoft;
  const std::string a = ExportMjcf(ShippedSimulationModel(), Placement{}, {}).xml;
  const std::string b = ExportMjcf(ShippedSimulationModel(), Placement{}, soft).xml;
  EXPECT_NE(a, b);
  EXPECT_EQ(a.size() > 0, b.size() > 0);
  EXPECT_EQ(ParseMujocoServo("soft", "x"), MujocoServo::kSoft);
  EXPECT_THROW(ParseMujocoServo("hard", "--mujoco-servo"), InputError);
}

TEST(MjcfExport, InvalidStepIsAnInputError) {
  MjcfOptions o;
  o.time_step = 0.0;
  EXPECT_THROW(ExportMjcf(ShippedSimulationModel(), Placement{}, o), InputError);
}

}  // namespace
}  // namespace graspsynth
