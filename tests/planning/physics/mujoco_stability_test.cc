// The MuJoCo stability backend against ODE: the same verdict on a box held in a clear power grasp
// and on a sphere released from an open hand; the MJCF it loads.
#include "planning/physics/mujoco_stability.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/planning/physics/test_hands.h"

namespace planning::physics {
namespace {

// A box (5 × 5 × 20 cm, 0.3 kg) lying on the claw's palm along x, as the test bottle.
SimObject Box() {
  SimObject o;
  SimShape s;
  s.kind = SimShape::Kind::kBox;
  s.size = Eigen::Vector3d(0.20, 0.05, 0.05);
  o.shapes.push_back(s);
  o.mass = 0.3;
  o.world_from_object.translation() = Eigen::Vector3d(0, 0, 0.026);
  return o;
}

// A ball (radius 3 cm, 0.1 kg) resting on the palm.
SimObject Ball() {
  SimObject o;
  SimShape s;
  s.kind = SimShape::Kind::kSphere;
  s.size = Eigen::Vector3d(0.03, 0, 0);
  o.shapes.push_back(s);
  o.mass = 0.1;
  o.world_from_object.translation() = Eigen::Vector3d(0, 0, 0.031);
  return o;
}

TEST(MujocoModelTest, WritesBodiesJointsActuators) {
  const std::string xml = MujocoModelXml(testing_hands::ClawHand(1.3), Box(), SimOptions{});
  EXPECT_NE(xml.find("<freejoint name=\"object_free\"/>"), std::string::npos);
  EXPECT_NE(xml.find("name=\"j15\" type=\"hinge\""), std::string::npos);  // 5 fingers × 3
  EXPECT_NE(xml.find("<velocity name=\"a15\""), std::string::npos);
  EXPECT_NE(xml.find("condim=\"4\""), std::string::npos);  // soft-finger patch by default
  SimOptions point = SimOptions{};
  point.contact_patch_radius = 0;
  EXPECT_NE(MujocoModelXml(testing_hands::ClawHand(1.3), Box(), point).find("condim=\"3\""),
            std::string::npos);
  SimObject empty;
  EXPECT_THROW(MujocoModelXml(testing_hands::ClawHand(1.3), empty, SimOptions{}),
               std::invalid_argument);
}

TEST(MujocoStabilityTest, EnginesAgreeOnAPowerGraspedBox) {
  if (!EngineAvailable(PhysicsEngine::kMujoco)) GTEST_SKIP() << "built without MuJoCo";
  const OdeRuntime ode;
  const SimHand hand = testing_hands::ClawHand(1.3);
  const StabilityOptions options;
  const StabilityResult a = TestGraspStabilityIn(PhysicsEngine::kOde, ode, hand, Box(), options);
  const StabilityResult b = TestGraspStabilityIn(PhysicsEngine::kMujoco, ode, hand, Box(), options);
  EXPECT_TRUE(a.stable) << a.message << " slip " << a.max_slip_m;
  EXPECT_TRUE(b.stable) << b.message << " slip " << b.max_slip_m << " rot " << b.max_rotation_deg
                        << " links " << b.closure_contact_links;
  EXPECT_EQ(b.directions_passed, 6);
  EXPECT_GE(b.closure_contact_links, 4);
  EXPECT_LT(b.max_slip_m, options.max_slip);
}

TEST(MujocoStabilityTest, EnginesAgreeOnABallFromAnOpenHand) {
  if (!EngineAvailable(PhysicsEngine::kMujoco)) GTEST_SKIP() << "built without MuJoCo";
  const OdeRuntime ode;
  const SimHand hand = testing_hands::ClawHand(-0.3);
  const StabilityOptions options;
  const StabilityResult a = TestGraspStabilityIn(PhysicsEngine::kOde, ode, hand, Ball(), options);
  const StabilityResult b =
      TestGraspStabilityIn(PhysicsEngine::kMujoco, ode, hand, Ball(), options);
  EXPECT_FALSE(a.stable);
  EXPECT_FALSE(b.stable);
  EXPECT_NE(b.status, StabilityStatus::kBlownUp) << b.message;
}

TEST(MujocoStabilityTest, DeterministicAndChecked) {
  if (!EngineAvailable(PhysicsEngine::kMujoco)) GTEST_SKIP() << "built without MuJoCo";
  StabilityOptions options;
  options.trial_time = 0.2;
  const SimHand hand = testing_hands::ClawHand(1.3);
  const StabilityResult a = TestGraspStabilityMujoco(hand, Box(), options);
  const StabilityResult b = TestGraspStabilityMujoco(hand, Box(), options);
  for (int d = 0; d < 6; ++d) EXPECT_EQ(a.directions[d].slip_m, b.directions[d].slip_m);
  options.trial_time = 0;
  EXPECT_THROW(TestGraspStabilityMujoco(hand, Box(), options), std::invalid_argument);
}

}  // namespace
}  // namespace planning::physics
