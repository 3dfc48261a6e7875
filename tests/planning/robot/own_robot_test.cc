// The walkthrough of docs/own-robot.md, step by step, on tinyarm (assets/robots/tinyarm): load
// the URDF with package:// meshes, find its SRDF, check with and without the SRDF, the named pose,
// the shipped scenario (start pose from the SRDF), plan with AICO and BiRRT, render a frame.
#include <gtest/gtest.h>

#include "base/assets.h"
#include "planning/motion/robot_scene.h"
#include "visualize/scene_builder.h"
#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/motion/planner.h"
#include "planning/robot/robot_io.h"
#include "planning/motion/scenario.h"
#include "planning/robot/srdf.h"
#include "render/offscreen_context.h"
#include "render/renderer.h"
#include "tests/planning/robot/robot_test_util.h"

namespace planning {
namespace {

const std::string kUrdf = AssetFile("robots/tinyarm/urdf/tinyarm.urdf");

bool Colliding(const Robot& robot, const Eigen::VectorXd& q, const CollisionOptions& options,
               ProximityPair* hit) {
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  CollisionData coll(robot, Environment{}, options);
  return InCollision(robot, kin, &coll, hit);
}

TEST(OwnRobot, Step1To3LoadMeshesSrdfAndPose) {
  const Robot robot = LoadRobot(kUrdf);
  EXPECT_EQ(DofNames(robot), (std::vector<std::string>{"joint1", "joint2", "joint3", "joint4",
                                                       "joint5", "finger_left_joint"}));
  EXPECT_EQ(robot.meshes.size(), 3u);  // base.stl, link.stl (shared), palm.dae
  ASSERT_EQ(robot.chains.size(), 1u);  // tinyarm.chains.json next to the URDF
  const std::string srdf_path = FindSrdf(kUrdf);
  ASSERT_NE(srdf_path, "");
  const Srdf srdf = LoadSrdf(srdf_path);
  CheckSrdf(srdf, robot);
  // Without the SRDF the closed fingers collide; with it the robot is collision-free.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(num_dofs(robot));
  ProximityPair hit;
  ASSERT_TRUE(Colliding(robot, zero, {}, &hit));
  const std::string pair = robot.links[hit.link_a].name + "/" + robot.links[hit.link_b].name;
  EXPECT_TRUE(pair == "finger_left/finger_right" || pair == "finger_right/finger_left") << pair;
  CollisionOptions with_srdf;
  with_srdf.disabled_pairs = DisabledPairs(srdf);
  EXPECT_FALSE(Colliding(robot, zero, with_srdf, &hit));
  const Eigen::VectorXd ready = NamedPose(robot, srdf, "ready");
  EXPECT_DOUBLE_EQ(ready[2], 0.8);
  EXPECT_FALSE(Colliding(robot, ready, with_srdf, &hit));
  // The app's loader finds the same SRDF and disables the same pairs.
  const planning::RobotScene scene = planning::LoadRobotScene(kUrdf, planning::RobotInputOptions{});
  ASSERT_TRUE(scene.srdf.has_value());
  EXPECT_EQ(scene.collision_options.disabled_pairs.size(), srdf.disabled_pairs.size());
  EXPECT_EQ(planning::ChooseQ(scene, "", "ready"), ready);
}

TEST(OwnRobot, Step5And6PlanWithAicoAndBiRrt) {
  ScenarioOverrides overrides;
  overrides.search_roots = {AssetFile("")};
  const auto scenario = LoadScenario(AssetFile("scenarios/tinyarm_ring.json"), overrides);
  const Srdf srdf = LoadSrdf(FindSrdf(kUrdf));
  EXPECT_EQ(scenario->initial.problem.q0, NamedPose(scenario->robot, srdf, "ready"));
  const PlanResult aico = RunPlanner(*scenario, Planner::kAico, 0);
  EXPECT_TRUE(aico.report.success);
  EXPECT_TRUE(aico.report.path_collision_free);
  // Through the ring: the total writhe of arm x loop changes by about a half turn or more.
  EXPECT_GT(std::abs(aico.report.final_writhe_total - aico.report.start_writhe_total), 0.25);
  const PlanResult birrt = RunPlanner(*scenario, Planner::kBiRrt, 0);
  EXPECT_TRUE(birrt.report.path_collision_free);
}

TEST(OwnRobot, Step6RenderAFrame) {
  render::OffscreenContext context(render::GlBackend::kAuto);
  render::Renderer renderer(context.proc_loader());
  const visualize::SceneDocument doc = visualize::RobotSceneDocument(AssetFile("scenarios/tinyarm_ring.json"),
                                                         "", "ready", planning::RobotInputOptions{});
  const render::Image image = renderer.Render(doc.scene, doc.camera, 96, 72, {});
  EXPECT_EQ(image.width, 96);
  // The scenario's box task is drawn (as in plan frames): one box more than the robot alone.
  const auto boxes = [](const render::Scene& scene) {
    int n = 0;
    for (const render::Shape& shape : scene.shapes) n += shape.kind == render::Shape::Kind::kBox;
    return n;
  };
  const visualize::SceneDocument robot_only = visualize::RobotSceneDocument(
      AssetFile("robots/tinyarm/urdf/tinyarm.urdf"), "", "ready", planning::RobotInputOptions{});
  EXPECT_EQ(boxes(doc.scene), boxes(robot_only.scene) + 1);
  // Something is drawn: not every pixel equals the first.
  bool varied = false;
  for (size_t i = 4; i < image.rgba.size() && !varied; i += 4)
    varied = image.rgba[i] != image.rgba[0];
  EXPECT_TRUE(varied);
}

}  // namespace
}  // namespace planning
