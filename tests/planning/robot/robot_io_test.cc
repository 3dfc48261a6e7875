// URDF loading: the shipped models, meshes through package:// URIs, chains, and clear errors.
#include "planning/robot/robot_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "tests/planning/robot/robot_test_util.h"

namespace planning {
namespace {

using ::testing::HasSubstr;

TEST(RobotIo, Lwr4SdhStructure) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  EXPECT_EQ(robot.name, "lwr4_sdh");
  ASSERT_EQ(num_dofs(robot), 14);  // 7 arm + 7 SDH (finger 2 knuckle is a mimic)
  const std::vector<std::string> expected = {"lwr_joint_1",
                                             "lwr_joint_2",
                                             "lwr_joint_3",
                                             "lwr_joint_4",
                                             "lwr_joint_5",
                                             "lwr_joint_6",
                                             "lwr_joint_7",
                                             "sdh_knuckle_joint",
                                             "sdh_finger_1_proximal_joint",
                                             "sdh_finger_1_distal_joint",
                                             "sdh_finger_2_proximal_joint",
                                             "sdh_finger_2_distal_joint",
                                             "sdh_thumb_proximal_joint",
                                             "sdh_thumb_distal_joint"};
  EXPECT_EQ(DofNames(robot), expected);
  EXPECT_EQ(robot.links[0].name, "lwr_base_link");
  // Topological order: every parent precedes its child.
  for (size_t l = 1; l < robot.links.size(); ++l) {
    const Joint& j = robot.joints[robot.links[l].parent_joint];
    EXPECT_EQ(j.child_link, static_cast<int>(l));
    EXPECT_LT(j.parent_link, static_cast<int>(l));
  }
  const Joint& mimic = robot.joints[FindJoint(robot, "sdh_finger_2_knuckle_joint")];
  EXPECT_TRUE(mimic.is_mimic);
  EXPECT_EQ(mimic.dof, 7);
  EXPECT_NEAR(LowerLimits(robot)[1], -120.0 * M_PI / 180.0, 1e-6);
  EXPECT_NEAR(UpperLimits(robot)[7], M_PI / 2, 1e-6);
  // Capsules come from <collision name="capsule"> cylinders.
  const Link& l2 = robot.links[FindLink(robot, "lwr_link_2")];
  ASSERT_EQ(l2.collisions.size(), 1u);
  EXPECT_EQ(l2.collisions[0].kind, Geometry::Kind::kCapsule);
  EXPECT_NEAR(l2.collisions[0].size[0], 0.07, 1e-12);
  EXPECT_NEAR(l2.collisions[0].size[1], 0.2, 1e-12);
  // Colours from top-level materials.
  EXPECT_NEAR(robot.links[FindLink(robot, "lwr_link_1")].visuals[0].rgba[0], 1.0f, 1e-6);
  // Chains from the sidecar.
  EXPECT_GE(robot.chains.size(), 4u);
  EXPECT_EQ(robot.chains[FindChain(robot, "sdh_thumb")].point_link.size(), 4u);
}

TEST(RobotIo, AdjacencySkipsJointNeighboursAndFixedAttachments) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  EXPECT_TRUE(AreAdjacent(robot, FindLink(robot, "lwr_link_2"), FindLink(robot, "lwr_link_3")));
  EXPECT_FALSE(AreAdjacent(robot, FindLink(robot, "lwr_link_2"), FindLink(robot, "lwr_link_4")));
  // Flange, adapter and palm are rigidly attached: the palm is adjacent to link 6 via joint 7.
  EXPECT_TRUE(AreAdjacent(robot, FindLink(robot, "sdh_palm"), FindLink(robot, "lwr_link_6")));
  EXPECT_TRUE(AreAdjacent(robot, FindLink(robot, "sdh_palm"), FindLink(robot, "lwr_link_7")));
  // The fixed thumb knuckle is part of the palm body, so the thumb proximal is adjacent to it.
  EXPECT_TRUE(
      AreAdjacent(robot, FindLink(robot, "sdh_thumb_proximal"), FindLink(robot, "sdh_palm")));
  EXPECT_FALSE(
      AreAdjacent(robot, FindLink(robot, "sdh_finger_1_proximal"), FindLink(robot, "sdh_palm")));
}

TEST(RobotIo, HumanHandHasTwentyFingerJointsAndPalmPose) {
  const Robot robot = LoadRobot(AssetFile("robots/human_hand.urdf"));
  ASSERT_EQ(num_dofs(robot), 26);
  EXPECT_EQ(DofNames(robot)[0], "hand_tx");
  EXPECT_EQ(DofNames(robot)[5], "hand_rx");
  EXPECT_EQ(DofNames(robot)[6], "index_mcp_abd");
  EXPECT_EQ(DofNames(robot)[25], "thumb_ip");
  for (const char* c : {"thumb", "index", "middle", "ring", "little"}) {
    EXPECT_EQ(robot.chains[FindChain(robot, c)].point_link.size(), 4u) << c;
  }
  // Massless frames between MCP abduction and flexion do not break adjacency.
  EXPECT_TRUE(AreAdjacent(robot, FindLink(robot, "index_proximal"), FindLink(robot, "hand_palm")));
  EXPECT_FALSE(AreAdjacent(robot, FindLink(robot, "index_middle"), FindLink(robot, "hand_palm")));
}

TEST(RobotIo, Arm20Structure) {
  const Robot robot = LoadRobot(AssetFile("robots/arm20_sdh.urdf"));
  EXPECT_EQ(num_dofs(robot), 27);
  EXPECT_EQ(robot.chains[FindChain(robot, "arm")].point_link.size(), 21u);
}

TEST(RobotIo, ObjectsLoadWithMeshesAndChains) {
  for (const char* name : {"pole", "ring", "torus", "cylinder", "bottle", "ball", "box", "mug"}) {
    SCOPED_TRACE(name);
    const Robot obj = LoadRobot(AssetFile(std::string("objects/") + name + ".urdf"));
    EXPECT_EQ(num_dofs(obj), 0);
    EXPECT_EQ(obj.links.size(), 1u);
    EXPECT_FALSE(obj.links[0].collisions.empty());
    EXPECT_FALSE(obj.chains.empty());
  }
  const Robot ring = LoadRobot(AssetFile("objects/ring.urdf"));
  ASSERT_EQ(ring.meshes.size(), 1u);
  EXPECT_GT(ring.meshes[0].triangles.size(), 1000u);
  EXPECT_TRUE(ring.chains[0].closed);
}

TEST(RobotIo, PackageUrisResolveStlAndDaeMeshes) {
  const Robot robot = LoadRobot(TestDataFile("fake_pkg/urdf/mesh_bot.urdf"));
  ASSERT_EQ(robot.meshes.size(), 2u);
  const Mesh& box = robot.meshes[robot.links[0].visuals[0].mesh];
  EXPECT_EQ(box.triangles.size(), 12u);
  Eigen::Vector3f lo = box.vertices[0], hi = box.vertices[0];
  for (const auto& v : box.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  EXPECT_TRUE((hi - lo).isApprox(Eigen::Vector3f(0.1f, 0.2f, 0.3f), 1e-5f));
  const Mesh& tet = robot.meshes[robot.links[1].visuals[0].mesh];
  EXPECT_EQ(tet.triangles.size(), 4u);
  // Z-up COLLADA stays in its own axes: the apex is on +z.
  float zmax = 0;
  for (const auto& v : tet.vertices) zmax = std::max(zmax, v.z());
  EXPECT_NEAR(zmax, 0.1f, 1e-6f);
  // Same file through an explicit package path from elsewhere.
  RobotLoadOptions options;
  options.package_paths = {TestDataFile("")};
  EXPECT_EQ(LoadRobot(TestDataFile("fake_pkg/urdf/mesh_bot.urdf"), options).meshes.size(), 2u);
}

// ---- Malformed files ----------------------------------------------------------------------------

std::string Wrap(const std::string& body) { return "<robot name=\"t\">\n" + body + "</robot>\n"; }

void ExpectError(const std::string& xml, const std::string& needle) {
  try {
    ParseRobot(xml, "bad.urdf", TestDataFile(""));
    ADD_FAILURE() << "no error, expected: " << needle;
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr(needle));
    EXPECT_THAT(e.what(), HasSubstr("bad.urdf"));
  }
}

const char* kTwoLinks = "<link name=\"a\"/>\n<link name=\"b\"/>\n";

TEST(RobotIoErrors, MissingChildLink) {
  ExpectError(
      Wrap(std::string(kTwoLinks) +
           "<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"c\"/></joint>\n"),
      "bad.urdf:4: joint 'j': child link 'c' does not exist");
}

TEST(RobotIoErrors, UnknownJointType) {
  ExpectError(
      Wrap(std::string(kTwoLinks) +
           "<joint name=\"j\" type=\"hinge\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"),
      "unknown joint type 'hinge'");
}

TEST(RobotIoErrors, FloatingJointOnlyAsTheFreeBase) {
  // Below the root (the ROS "world" link + floating joint convention): the free base.
  const Robot robot = ParseRobot(
      Wrap(std::string(kTwoLinks) +
           "<joint name=\"j\" type=\"floating\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"),
      "bad.urdf", TestDataFile(""));
  EXPECT_EQ(robot.base_type, BaseType::kFloating);
  EXPECT_EQ(robot.base_joint, "j");
  EXPECT_EQ(num_dofs(robot), 0);  // the base pose is given apart from q (--base)
  const Robot planar = ParseRobot(
      Wrap(std::string(kTwoLinks) +
           "<joint name=\"p\" type=\"planar\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"),
      "bad.urdf", TestDataFile(""));
  EXPECT_EQ(planar.base_type, BaseType::kPlanar);
  // Inside the tree it is not a base: refused, naming the joint.
  ExpectError(
      Wrap("<link name=\"r\"/>" + std::string(kTwoLinks) +
           "<joint name=\"j0\" type=\"fixed\"><parent link=\"r\"/><child link=\"a\"/></joint>\n"
           "<joint name=\"j\" type=\"floating\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"),
      "joint 'j': a floating joint is supported only as the free base");
}

TEST(RobotIoErrors, Cycle) {
  ExpectError(
      Wrap("<link name=\"r\"/>" + std::string(kTwoLinks) +
           "<joint name=\"j1\" type=\"fixed\"><parent link=\"r\"/><child link=\"a\"/></joint>\n"
           "<joint name=\"j2\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
           "<joint name=\"j3\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint>\n"),
      "only one parent");
  ExpectError(
      Wrap(std::string(kTwoLinks) +
           "<joint name=\"j1\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
           "<joint name=\"j2\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint>\n"),
      "kinematic cycle");
}

TEST(RobotIoErrors, TwoRoots) { ExpectError(Wrap(kTwoLinks), "2 roots (a, b)"); }

TEST(RobotIoErrors, RevoluteWithoutLimit) {
  ExpectError(
      Wrap(std::string(kTwoLinks) +
           "<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"),
      "needs a <limit");
}

TEST(RobotIoErrors, MimicOfUnknownJointWarnsAndMovesOnItsOwn) {
  const Robot robot = ParseRobot(
      Wrap(std::string(kTwoLinks) +
           "<joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>"
           "<mimic joint=\"nope\"/></joint>\n"),
      "bad.urdf", TestDataFile(""));
  ASSERT_EQ(robot.warnings.size(), 1u);
  EXPECT_THAT(robot.warnings[0], HasSubstr("mimics unknown joint 'nope'"));
  EXPECT_THAT(robot.warnings[0], HasSubstr("bad.urdf"));
  EXPECT_EQ(num_dofs(robot), 1);
}

TEST(RobotIoErrors, MissingMeshFile) {
  ExpectError(Wrap("<link name=\"a\"><visual><geometry><mesh filename=\"package://fake_pkg/meshes/"
                   "missing.stl\"/></geometry></visual></link>\n"),
              "mesh 'package://fake_pkg/meshes/missing.stl' not found");
  ExpectError(Wrap("<link name=\"a\"><visual><geometry><mesh filename=\"no/such.stl\"/>"
                   "</geometry></visual></link>\n"),
              "mesh file 'no/such.stl' not found");
}

TEST(RobotIoErrors, XmlSyntaxAndDuplicates) {
  ExpectError("<robot name=\"t\"><link name=\"a\">\n</robot>", "XML error");
  ExpectError(Wrap("<link name=\"a\"/>\n<link name=\"a\"/>\n"), "duplicate link 'a'");
  ExpectError("<robot name=\"t\"/>", "has no <link>");
}

TEST(RobotIoErrors, MissingFile) {
  EXPECT_THROW(LoadRobot("/nonexistent/robot.urdf"), std::invalid_argument);
}

TEST(RobotIoErrors, ChainSidecarErrorsNameTheJsonPath) {
  Robot robot = LoadRobot(AssetFile("objects/box.urdf"));
  const std::string path = std::string(TOPOPLAN_BINARY_DIR) + "/bad_chains.json";
  {
    std::ofstream out(path);
    out << R"({"chains": [{"name": "c", "points": [{"link": "box"}, {"link": "nolink"}]}]})";
  }
  try {
    LoadChains(path, &robot);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("chains[0].points[1].link: unknown link 'nolink' (links: box)"));
  }
}

}  // namespace
}  // namespace planning
