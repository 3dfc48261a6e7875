// Golden images of every robot and the objects at fixed poses (snapshots/robots/<case>.png,
// 320x240), built through app::BuildRobotScene, the same path as `topoplan render ROBOT.urdf`.
// UPDATE_SNAPSHOTS=1 rewrites them; failures write actual/expected/diff images into
// <build>/snapshot-diff/robots/.
#include <gtest/gtest.h>

#include <cmath>

#include "visualize/scene_builder.h"
#include "planning/robot/robot_io.h"
#include "render/diff.h"
#include "tests/planning/robot/robot_test_util.h"
#include "tests/render/gl_fixture.h"

namespace planning {
namespace {

constexpr int kW = 320, kH = 240;

void ExpectSnapshot(const render::Scene& scene, const render::Camera& camera,
                    const std::string& name) {
  const render::Image image = render::testing::SharedRenderer().Render(scene, camera, kW, kH);
  const std::string golden =
      std::string(TOPOPLAN_SOURCE_DIR) + "/snapshots/robots/" + name + ".png";
  const std::string artefacts = std::string(TOPOPLAN_BINARY_DIR) + "/snapshot-diff/robots";
  const render::SnapshotResult r = render::CheckSnapshot(image, golden, artefacts);
  EXPECT_TRUE(r.passed) << "robots/" << name << ": " << r.message;
  std::printf("robots/%s: %s\n", name.c_str(), r.message.c_str());
}

render::Camera Look(float ex, float ey, float ez, float tx, float ty, float tz, float fovy) {
  render::Camera c;
  c.eye = Eigen::Vector3f(ex, ey, ez);
  c.target = Eigen::Vector3f(tx, ty, tz);
  c.fovy_deg = fovy;
  return c;
}

render::Scene Build(const Robot& robot, const Eigen::VectorXd& q, const Environment& env,
                    visualize::SceneMeshCache* cache) {
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  return visualize::BuildRobotScene(robot, kin, env, {}, cache);
}

Eigen::VectorXd Q(std::initializer_list<double> v) {
  Eigen::VectorXd q(v.size());
  int k = 0;
  for (double x : v) q[k++] = x;
  return q;
}

// LWR4 + SDH reaching forward with a spherical (60°) hand, flexed fingers.
TEST(RobotSnapshot, Lwr4Sdh) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  visualize::SceneMeshCache cache;
  const Eigen::VectorXd q =
      Q({0.3, 0.7, 0, -1.1, 0, 0.8, 0, M_PI / 3, 0.4, 0.5, 0.4, 0.5, 0.4, 0.5});
  const render::Scene scene = Build(robot, q, {}, &cache);
  ExpectSnapshot(scene, visualize::FrameSceneCamera(scene), "lwr4_sdh");
}

// Close-up of the SDH on the flange: knuckles on the palm, fingers in the spherical pose
// (axis 0 = 60°: three fingers at 120°), proximal/distal flexed towards the grasp centre.
TEST(RobotSnapshot, SdhCloseUp) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  visualize::SceneMeshCache cache;
  const Eigen::VectorXd q = Q({0, 0, 0, 0, 0, 0, 0, M_PI / 3, 0.3, 0.4, 0.3, 0.4, 0.3, 0.4});
  const render::Scene scene = Build(robot, q, {}, &cache);
  ExpectSnapshot(scene, Look(0.30, -0.36, 1.50, 0, 0, 1.30, 38), "sdh_closeup");
}

// The 20-link arm coiled around the rope (thesis §4.3.1) at q = 0, with its chain.
TEST(RobotSnapshot, Arm20CoilAroundRope) {
  const Robot robot = LoadRobot(AssetFile("robots/arm20_sdh.urdf"));
  Environment env;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(-0.1, -1.7, 1.85));
  pose.rotate(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  AddObject(LoadRobot(AssetFile("objects/pole.urdf")), pose, "rope", &env);
  visualize::SceneMeshCache cache;
  const render::Scene scene = Build(robot, Eigen::VectorXd::Zero(num_dofs(robot)), env, &cache);
  ExpectSnapshot(scene, Look(3.6, -4.2, 3.0, -0.1, -1.3, 1.4, 40), "arm20_coil");
}

// Human hand: rest pose, and a power grasp (fingers flexed, thumb opposed).
TEST(RobotSnapshot, HumanHand) {
  const Robot robot = LoadRobot(AssetFile("robots/human_hand.urdf"));
  visualize::SceneMeshCache cache;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot));
  q[2] = 0.02;  // hand_tz: lift the palm off the grid
  ExpectSnapshot(Build(robot, q, {}, &cache), Look(0.22, -0.32, 0.24, 0, 0, 0.1, 38),
                 "human_hand_rest");
  const std::vector<std::string> names = DofNames(robot);
  auto dof = [&](const std::string& n) { return robot.joints[FindJoint(robot, n)].dof; };
  for (int k = 0; k < num_dofs(robot); ++k) {
    const std::string& n = names[k];
    if (n.find("_mcp_flex") != std::string::npos) q[k] = 0.9;
    if (n.find("_pip") != std::string::npos) q[k] = 1.0;
    if (n.find("_dip") != std::string::npos) q[k] = 0.6;
  }
  q[dof("thumb_cmc_abd")] = 0.8;
  q[dof("thumb_cmc_flex")] = 0.5;
  q[dof("thumb_mcp")] = 0.4;
  q[dof("thumb_ip")] = 0.4;
  ExpectSnapshot(Build(robot, q, {}, &cache), Look(0.32, -0.22, 0.2, 0, -0.02, 0.09, 38),
                 "human_hand_grasp");
}

// Every object in a row, with its chains.
TEST(RobotSnapshot, Objects) {
  const Robot empty = ParseRobot("<robot name=\"none\"><link name=\"world\"/></robot>", "none", "");
  Environment env;
  const char* names[] = {"cylinder", "bottle", "ball", "box", "mug", "torus"};
  for (int i = 0; i < 6; ++i) {
    double z = 0.0;
    if (std::string(names[i]) == "cylinder") z = 0.104;
    if (std::string(names[i]) == "ball") z = 0.0335;
    if (std::string(names[i]) == "box") z = 0.05;
    if (std::string(names[i]) == "torus") z = 0.012;
    AddObject(LoadRobot(AssetFile(std::string("objects/") + names[i] + ".urdf")),
              Eigen::Isometry3d(Eigen::Translation3d(0.12 * i, 0, z)), names[i], &env);
  }
  visualize::SceneMeshCache cache;
  const render::Scene scene = Build(empty, Eigen::VectorXd(0), env, &cache);
  ExpectSnapshot(scene, Look(0.3, -0.75, 0.4, 0.3, 0, 0.06, 40), "objects");
}

}  // namespace
}  // namespace planning
