#include "simulation/simulation_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

TEST(SimulationOptions, DefaultsAreValidAndBadValuesAreNamed) {
  std::string why;
  EXPECT_TRUE(SimulationOptions{}.IsValid(&why)) << why;
  SimulationOptions o;
  o.contact_kp = -1.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("contact_kp"), std::string::npos);
  o = {};
  o.max_contacts_per_pair = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("max_contacts_per_pair"), std::string::npos);
  GS_EXPECT_THROW_WITH(LoadDefaultSimulationModel(o), InputError, "max_contacts_per_pair");
}

TEST(SimulationModel, ObjectInertiaIsThatOfThePanAndItsHandle) {
  const SimulationModel model = LoadDefaultSimulationModel();
  const ObjectModel& o = model.scene().object;
  const ObjectInertia& in = model.object_inertia();
  const double body_mass = o.parts[0].mass, handle_mass = o.parts[1].mass;
  EXPECT_DOUBLE_EQ(in.mass, body_mass + handle_mass);
  // the handle's centre lies halfway along it, 2 cm above the pan's centre.
  const HandleAxis& h = *o.handle;
  const double r = 0.5 * (h.start_radius + h.end_radius);
  EXPECT_NEAR(in.p_OC.x(), handle_mass * r / in.mass, 1e-12);
  EXPECT_NEAR(in.p_OC.z(), handle_mass * (h.axis_height - o.rest_height) / in.mass, 1e-12);
  // symmetric positive definite, with the long axis (x) the easiest to turn about.
  EXPECT_TRUE(testing::MatricesNear(in.I_C, in.I_C.transpose(), 1e-15));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(in.I_C);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  EXPECT_LT(in.I_C(0, 0), in.I_C(1, 1));
  EXPECT_LT(in.I_C(0, 0), in.I_C(2, 2));
}

}  // namespace
}  // namespace graspsynth
