// Golden images of the ODE stability-test frames (snapshots/grasp/): the claw hand closed on the
// bottle, and the same hand with gravity pulling the bottle out of the open hand.
#include <gtest/gtest.h>

#include <cstdio>

#include "visualize/grasp_scene.h"
#include "planning/physics/grasp_simulation.h"
#include "render/diff.h"
#include "tests/planning/physics/test_hands.h"
#include "tests/render/gl_fixture.h"

namespace planning::physics {
namespace {

constexpr int kW = 320, kH = 240;

void ExpectSnapshot(const render::Scene& scene, const std::string& name) {
  render::Camera camera;
  camera.eye = Eigen::Vector3f(0.22f, -0.26f, 0.2f);
  camera.target = Eigen::Vector3f(0.0f, 0.0f, 0.04f);
  camera.fovy_deg = 40.0f;
  const render::Image image = render::testing::SharedRenderer().Render(scene, camera, kW, kH);
  const std::string golden = std::string(TOPOPLAN_SOURCE_DIR) + "/snapshots/grasp/" + name + ".png";
  const std::string artefacts = std::string(TOPOPLAN_BINARY_DIR) + "/snapshot-diff/grasp";
  const render::SnapshotResult r = render::CheckSnapshot(image, golden, artefacts);
  EXPECT_TRUE(r.passed) << "grasp/" << name << ": " << r.message;
  std::printf("grasp/%s: %s\n", name.c_str(), r.message.c_str());
}

TEST(GraspSnapshotTest, ClawClosedOnTheBottleWithContacts) {
  OdeRuntime runtime;
  const SimHand hand = testing_hands::ClawHand(1.3);
  const SimObject bottle = testing_hands::Bottle();
  GraspSimulation sim(runtime, hand, bottle, {});
  for (int k = 0; k < 500; ++k) sim.Step();
  ASSERT_GE(sim.state().num_contact_links, 5);
  ExpectSnapshot(visualize::GraspSimScene(hand, bottle, sim.state(), Eigen::Vector3d::Zero()),
                 "claw_closed");
  // The open hand under gravity along +z of the palm: the bottle has left the palm.
  GraspSimulation open(runtime, testing_hands::ClawHand(-0.3), bottle, {});
  const Eigen::Vector3d g(0, 0, 9.81);
  open.SetGravity(g);
  for (int k = 0; k < 150; ++k) open.Step();
  ASSERT_GT(open.state().world_from_object.translation().z(), 0.08);
  ExpectSnapshot(visualize::GraspSimScene(testing_hands::ClawHand(-0.3), bottle, open.state(), g),
                 "open_hand_drops");
}

}  // namespace
}  // namespace planning::physics
