// Robot model → ODE description, and the end-to-end transfer + stability check of the power grasp.
#include "planning/physics/hand_builder.h"

#include <gtest/gtest.h>

#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/stability.h"
#include "planning/robot/robot_io.h"

namespace planning::physics {
namespace {

const std::string kAssets = std::string(TOPOPLAN_SOURCE_DIR) + "/assets/";

class HandBuilderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { runtime_ = new OdeRuntime(); }
  static void TearDownTestSuite() {
    delete runtime_;
    runtime_ = nullptr;
  }
  static OdeRuntime* runtime_;
};
OdeRuntime* HandBuilderTest::runtime_ = nullptr;

TEST_F(HandBuilderTest, SdhBecomesPalmPlusEightHinges) {
  const Robot lwr = LoadRobot(kAssets + "robots/lwr4_sdh.urdf");
  const Robot sdh = MakeFloatingHand(lwr, "sdh_palm", Eigen::Matrix3d::Identity());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(sdh));
  q[6] = 0.5;  // spread
  q[7] = 0.4;  // a flexion joint
  const SimHand hand = BuildSimHand(sdh, q, "sdh_palm");
  // palm (with the fixed thumb knuckle) + 2 rotating knuckles + 6 phalanges.
  ASSERT_EQ(hand.links.size(), 9u);
  EXPECT_EQ(hand.links[0].name, "sdh_palm");
  int held = 0, opened = 0;
  for (size_t i = 1; i < hand.links.size(); ++i) {
    const SimHandLink& l = hand.links[i];
    EXPECT_FALSE(l.shapes.empty()) << l.name;
    if (l.name.find("knuckle") != std::string::npos) {
      EXPECT_NEAR(l.q_start, 0.5, 1e-12) << l.name;  // spread held, mimic follows the master
      EXPECT_NEAR(l.q_target, 0.5, 1e-12) << l.name;
      ++held;
    } else if (std::abs(l.q_target - l.q_start - 0.25) < 1e-12) {
      ++opened;  // opened by 0.1, driven to the grasp value + 0.15
    }
  }
  EXPECT_EQ(held, 2);
  EXPECT_EQ(opened, 6);
  EXPECT_THROW(BuildSimHand(sdh, Eigen::VectorXd::Zero(3), "sdh_palm"), std::invalid_argument);
}

TEST_F(HandBuilderTest, TorusBecomesARingOfCapsules) {
  const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  const SimObject torus =
      BuildSimObject(FindGraspObject(objects, "torus"), Eigen::Isometry3d::Identity(), 16);
  ASSERT_EQ(torus.shapes.size(), 16u);
  for (const SimShape& s : torus.shapes) {
    EXPECT_EQ(s.kind, SimShape::Kind::kCapsule);
    EXPECT_NEAR(s.body_from_shape.translation().head<2>().norm(), 0.045 * std::cos(M_PI / 16),
                1e-9);
  }
}

TEST_F(HandBuilderTest, TransferredPowerGraspHoldsTheBottleInAllSixDirections) {
  const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  const Robot human = LoadRobot(kAssets + "robots/human_hand.urdf");
  const Robot lwr = LoadRobot(kAssets + "robots/lwr4_sdh.urdf");
  const HumanGrasp g = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  const GraspObject& bottle = FindGraspObject(objects, "bottle");
  const TransferSetup setup = MakeTransferSetup(human, lwr, bottle, g);
  const TransferResult t = TransferGrasp(setup, TransferMethod::kWinding);
  const StabilityResult r =
      TestGraspStability(*runtime_, BuildSimHand(setup.sdh, t.q, "sdh_palm"),
                         BuildSimObject(bottle, g.world_from_object), StabilityOptions{});
  EXPECT_EQ(r.status, StabilityStatus::kTested) << r.message;
  EXPECT_EQ(r.directions_passed, 6);
  EXPECT_TRUE(r.stable);
}

}  // namespace
}  // namespace planning::physics
