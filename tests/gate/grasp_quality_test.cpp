#include "gate/grasp_quality.hpp"

#include <gtest/gtest.h>

namespace graspsynth {
namespace {

// contacts at the centres of the six faces of a cube of half-side h centred at c, normals
// pointing inward.
std::vector<GraspContact> CubeFaceContacts(double h, double mu,
                                           const Eigen::Vector3d& c = Eigen::Vector3d::Zero()) {
  std::vector<GraspContact> contacts;
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {-1.0, 1.0}) {
      GraspContact k;
      k.p_WC = c + side * h * Eigen::Vector3d::Unit(axis);
      k.n_W = -side * Eigen::Vector3d::Unit(axis);
      k.mu = mu;
      contacts.push_back(k);
    }
  }
  return contacts;
}

TEST(GraspQuality, EnclosingFrictionalContactsAreForceClosure) {
  const GraspQuality q = EvaluateGraspQuality(CubeFaceContacts(0.05, 0.5), Eigen::Vector3d::Zero());
  EXPECT_TRUE(q.force_closure) << q.message;
  EXPECT_GT(q.epsilon, 0.05);
  EXPECT_GT(q.volume, 0.0);
  EXPECT_EQ(q.wrenches, 48);
  EXPECT_GT(q.facets, 0);
}

TEST(GraspQuality, ContactsOnOneSideAreNotForceClosure) {
  std::vector<GraspContact> contacts;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.05, 0, -0.05), Eigen::Vector3d(-0.05, 0.05, -0.05),
        Eigen::Vector3d(-0.05, -0.05, -0.05)}) {
    contacts.push_back({p, Eigen::Vector3d::UnitZ(), 0.8});
  }
  const GraspQuality q = EvaluateGraspQuality(contacts, Eigen::Vector3d::Zero());
  EXPECT_FALSE(q.force_closure);
  EXPECT_LE(q.epsilon, 0.0);
}

TEST(GraspQuality, DegenerateWrenchSetsHaveNoInterior) {
  const GraspQuality one =
      EvaluateGraspQuality({CubeFaceContacts(0.05, 0.5)[0]}, Eigen::Vector3d::Zero());
  EXPECT_FALSE(one.force_closure);
  EXPECT_EQ(one.epsilon, 0.0);
  EXPECT_EQ(one.volume, 0.0);
  EXPECT_FALSE(one.message.empty());
  // frictionless face-centre contacts push through the centre: no torque at all.
  const GraspQuality frictionless =
      EvaluateGraspQuality(CubeFaceContacts(0.05, 0.0), Eigen::Vector3d::Zero());
  EXPECT_FALSE(frictionless.force_closure);
  EXPECT_EQ(frictionless.epsilon, 0.0);
}

TEST(GraspQuality, MoreFrictionGivesAHigherEpsilon) {
  double previous = 0.0;
  for (double mu : {0.2, 0.5, 1.0}) {
    const GraspQuality q =
        EvaluateGraspQuality(CubeFaceContacts(0.05, mu), Eigen::Vector3d::Zero());
    EXPECT_GT(q.epsilon, previous) << "mu " << mu;
    previous = q.epsilon;
  }
}

TEST(GraspQuality, IndependentOfObjectSizeAndPlacementWithTheAutomaticTorqueScale) {
  const GraspQuality small =
      EvaluateGraspQuality(CubeFaceContacts(0.05, 0.5), Eigen::Vector3d::Zero());
  const Eigen::Vector3d c(0.3, -0.2, 1.0);
  const GraspQuality large = EvaluateGraspQuality(CubeFaceContacts(0.2, 0.5, c), c);
  EXPECT_NEAR(large.epsilon, small.epsilon, 1e-9);
  EXPECT_NEAR(large.volume, small.volume, 1e-9 * small.volume);
  EXPECT_NEAR(large.torque_scale, 0.2, 1e-15);
}

TEST(GraspQualityOptions, RejectsTooFewConeEdges) {
  GraspQualityOptions o;
  o.cone_edges = 2;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, "GraspQualityOptions::cone_edges must be at least 3");
}

}  // namespace
}  // namespace graspsynth
