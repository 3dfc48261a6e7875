// SRDF reading and its effect on collision checks; URDF input limits (nesting depth, size,
// geometry urdfdom would drop, package:// confinement).
#include "planning/robot/srdf.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"
#include "tests/planning/robot/robot_test_util.h"

namespace planning {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Two boxes, base and tip, two joints apart (mid has a small sphere far above, so base and tip
// are not adjacent): near q = 0 they overlap.
const char* kTwoBoxes = R"(<robot name="two">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="mid"><collision><origin xyz="0 0 1"/><geometry><sphere radius="0.01"/></geometry>
  </collision></link>
  <link name="tip"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="mid"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="turn" type="revolute"><parent link="mid"/><child link="tip"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

const char* kTwoBoxesSrdf = R"(<?xml version="1.0"?>
<robot name="two">
  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base"/>
  <group name="all"><chain base_link="base" tip_link="tip"/></group>
  <group_state name="apart" group="all">
    <joint name="slide" value="0.5"/>
    <joint name="turn" value="-0.25"/>
    <joint name="world_joint" value="0 0 0 0 0 0 1"/>
  </group_state>
  <passive_joint name="turn"/>
  <disable_collisions link1="base" link2="tip" reason="Never"/>
</robot>)";

Robot TwoBoxes() { return ParseRobot(kTwoBoxes, "two.urdf", ""); }

std::string Message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Srdf, ParsesPairsPosesAndListsIgnoredJoints) {
  const Srdf s = ParseSrdf(kTwoBoxesSrdf, "two.srdf");
  EXPECT_EQ(s.robot_name, "two");
  ASSERT_EQ(s.disabled_pairs.size(), 1u);
  EXPECT_EQ(s.disabled_pairs[0].link1, "base");
  EXPECT_EQ(s.disabled_pairs[0].link2, "tip");
  EXPECT_EQ(s.disabled_pairs[0].line, 11);
  ASSERT_EQ(s.poses.size(), 1u);
  EXPECT_EQ(s.poses[0].name, "apart");
  EXPECT_EQ(s.poses[0].joints.size(), 3u);
  EXPECT_EQ(s.passive_joints, std::vector<std::string>{"turn"});
  ASSERT_EQ(s.virtual_joints.size(), 1u);
  EXPECT_EQ(s.virtual_joints[0].name, "world_joint");
  const Robot robot = TwoBoxes();
  CheckSrdf(s, robot);
  const Eigen::VectorXd q = NamedPose(robot, s, "apart");
  ASSERT_EQ(q.size(), 2);
  EXPECT_DOUBLE_EQ(q[0], 0.5);
  EXPECT_DOUBLE_EQ(q[1], -0.25);
  EXPECT_THAT(Message([&] { NamedPose(robot, s, "home"); }),
              HasSubstr("no group_state named 'home' (have: apart)"));
}

TEST(Srdf, MalformedIsAnErrorUnknownNamesAreWarningsWithLines) {
  EXPECT_THAT(Message([] { ParseSrdf("<robot>\n<disable_collisions link1=\"a\"/>", "m.srdf"); }),
              HasSubstr("m.srdf:"));
  EXPECT_THAT(
      Message([] { ParseSrdf("<robot>\n<disable_collisions link1=\"a\"/>\n</robot>", "m.srdf"); }),
      HasSubstr("m.srdf:2: <disable_collisions> needs link1= and link2="));
  EXPECT_THAT(Message([] {
                ParseSrdf(
                    "<robot>\n<group_state name=\"p\">\n<joint name=\"j\" value=\"abc\"/>"
                    "</group_state></robot>",
                    "m.srdf");
              }),
              HasSubstr("m.srdf:3: group_state 'p' joint 'j': value= must be finite numbers"));
  const Srdf bad = ParseSrdf(
      "<robot>\n<disable_collisions link1=\"base\" link2=\"nose\"/>\n"
      "<group_state name=\"p\"><joint name=\"elbow\" value=\"1\"/></group_state></robot>",
      "bad.srdf");
  // Names the robot lacks are warnings (skipped, as MoveIt skips them), one per name with its line.
  const std::vector<std::string> w = CheckSrdf(bad, TwoBoxes());
  ASSERT_EQ(w.size(), 2u);
  EXPECT_THAT(w[0], HasSubstr("bad.srdf:2: link 'nose' is not part of robot"));
  EXPECT_THAT(w[1], HasSubstr("bad.srdf:3: joint 'elbow' of group_state 'p' is not part of robot"));
  const Robot two = TwoBoxes();
  EXPECT_TRUE(DisabledPairs(bad, &two).empty());  // the pair with 'nose' is skipped
  EXPECT_EQ(NamedPose(two, bad, "p"), Eigen::VectorXd::Zero(num_dofs(two)));
  // An SRDF written for another robot is a warning too.
  const Srdf other = ParseSrdf("<robot name=\"ur5\"/>", "other.srdf");
  const std::vector<std::string> w2 = CheckSrdf(other, TwoBoxes());
  ASSERT_EQ(w2.size(), 1u);
  EXPECT_THAT(w2[0], HasSubstr("written for robot 'ur5'"));
  // One document per file; a value's arity is the joint's.
  EXPECT_THAT(Message([] { ParseSrdf("<robot/>\n<robot/>", "two.srdf"); }),
              HasSubstr("two.srdf:2: a second top-level element <robot>"));
  EXPECT_THAT(Message([] { ParseSrdf("<robot/>\ngarbage", "tail.srdf"); }), HasSubstr("tail.srdf"));
  const Srdf pair = ParseSrdf(
      "<robot>\n<group_state name=\"p\"><joint name=\"slide\" value=\"0.1 0.2\"/>"
      "</group_state></robot>",
      "pair.srdf");
  EXPECT_THAT(
      Message([&] { NamedPose(TwoBoxes(), pair, "p"); }),
      HasSubstr("pair.srdf:2: group_state 'p' joint 'slide': value= has 2 numbers, the joint "
                "takes 1"));
}

TEST(Srdf, DisabledPairIsNotReported) {
  const Robot robot = TwoBoxes();
  const Srdf s = ParseSrdf(kTwoBoxesSrdf, "two.srdf");
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::Vector2d(0.05, 0.0), &kin);
  CollisionData plain(robot, Environment{});
  ProximityPair hit;
  ASSERT_TRUE(InCollision(robot, kin, &plain, &hit));
  EXPECT_EQ(robot.links[hit.link_a].name + robot.links[hit.link_b].name == "basetip" ||
                robot.links[hit.link_a].name + robot.links[hit.link_b].name == "tipbase",
            true);
  CollisionOptions options;
  options.disabled_pairs = DisabledPairs(s);
  CollisionData with_srdf(robot, Environment{}, options);
  std::vector<ProximityPair> pairs;
  ComputeProximity(robot, kin, 1.0, &with_srdf, &pairs);
  EXPECT_TRUE(pairs.empty());
  EXPECT_FALSE(InCollision(robot, kin, &with_srdf));
}

TEST(Srdf, FindSrdfNextToUrdfOrInSiblingFolder) {
  const fs::path dir = fs::temp_directory_path() / "topoplan_srdf_find";
  fs::remove_all(dir);
  fs::create_directories(dir / "urdf");
  fs::create_directories(dir / "srdf");
  std::ofstream(dir / "urdf" / "r.urdf") << kTwoBoxes;
  EXPECT_EQ(FindSrdf((dir / "urdf" / "r.urdf").string()), "");
  std::ofstream(dir / "srdf" / "r.srdf") << kTwoBoxesSrdf;
  EXPECT_EQ(FindSrdf((dir / "urdf" / "r.urdf").string()), (dir / "srdf" / "r.srdf").string());
  std::ofstream(dir / "urdf" / "r.srdf") << kTwoBoxesSrdf;
  EXPECT_EQ(FindSrdf((dir / "urdf" / "r.urdf").string()), (dir / "urdf" / "r.srdf").string());
  fs::remove_all(dir);
}

// ---- Free bases --------------------------------------------------------------------------------

// A body with an arm and no world link: as humanoids and quadrupeds ship.
const char* kFlyer = R"(<robot name="flyer">
  <link name="body"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="0 0 0.3"/><geometry><sphere radius="0.05"/></geometry>
  </collision></link>
  <joint name="shoulder" type="revolute"><parent link="body"/><child link="arm"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

TEST(SrdfBase, VirtualJointMakesAFloatingBaseWhosePoseIsNotInQ) {
  Robot robot = ParseRobot(kFlyer, "flyer.urdf", "");
  const Srdf s = ParseSrdf(R"(<robot name="flyer">
  <virtual_joint name="world_joint" type="floating" parent_frame="world" child_link="body"/>
  <group_state name="up" group="all">
    <joint name="world_joint" value="1 2 3 0 0 0.70710678 0.70710678"/>
    <joint name="shoulder" value="0.5"/>
  </group_state>
</robot>)",
                           "flyer.srdf");
  ASSERT_EQ(s.virtual_joints.size(), 1u);
  EXPECT_EQ(s.virtual_joints[0].type, "floating");
  EXPECT_TRUE(ApplySrdfBase(s, &robot).empty());
  EXPECT_EQ(robot.base_type, BaseType::kFloating);
  EXPECT_EQ(robot.base_joint, "world_joint");
  EXPECT_EQ(num_dofs(robot), 1);
  std::vector<std::string> warnings;
  const Eigen::VectorXd q = NamedPose(robot, s, "up", &warnings);
  EXPECT_TRUE(warnings.empty());
  EXPECT_DOUBLE_EQ(q[0], 0.5);
  const std::optional<Eigen::Isometry3d> base = NamedBasePose(robot, s, "up");
  ASSERT_TRUE(base.has_value());
  robot.world_from_root = *base;
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(1), &kin);
  // Body at (1, 2, 3) turned 90° about z; the arm's sphere 0.3 above it.
  EXPECT_TRUE(kin.world_from_link[0].translation().isApprox(Eigen::Vector3d(1, 2, 3), 1e-9));
  EXPECT_TRUE((kin.world_from_link[0].linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d::UnitY(), 1e-6));
}

TEST(SrdfBase, PinocchioRootJointAndPlanarBase) {
  Robot robot = ParseRobot(kFlyer, "flyer.urdf", "");
  const Srdf pin = ParseSrdf(R"(<robot name="flyer">
  <group_state name="standing" group="all">
    <joint name="root_joint" value="0 0 0.6 0 0 0 1"/><joint name="shoulder" value="0"/>
  </group_state>
</robot>)",
                             "pin.srdf");
  ApplySrdfBase(pin, &robot);
  EXPECT_EQ(robot.base_type, BaseType::kFloating);
  EXPECT_EQ(robot.base_joint, "root_joint");
  EXPECT_TRUE(
      NamedBasePose(robot, pin, "standing")->translation().isApprox(Eigen::Vector3d(0, 0, 0.6)));
  // Planar: x, y, theta.
  const Eigen::Isometry3d planar =
      BasePoseFromValues(BaseType::kPlanar, {1.0, -1.0, M_PI / 2}, "test");
  EXPECT_TRUE(planar.translation().isApprox(Eigen::Vector3d(1, -1, 0)));
  EXPECT_TRUE((planar.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_THAT(Message([] {
                BasePoseFromValues(BaseType::kFloating, {1, 2}, "--base");
              }),
              HasSubstr("--base"));
  EXPECT_THAT(Message([] {
                BasePoseFromValues(BaseType::kFloating, {0, 0, 0, 0, 0, 0, 0}, "--base");
              }),
              HasSubstr("--base"));
  EXPECT_THAT(Message([] {
                ParseSrdf(
                    "<robot name=\"f\">\n<virtual_joint name=\"v\" type=\"spherical\" "
                    "parent_frame=\"w\" child_link=\"body\"/>\n</robot>",
                    "v.srdf");
              }),
              HasSubstr("v.srdf:2"));
}

TEST(SrdfBase, FixedJointValuesAreSkippedWithAWarning) {
  // A group_state giving 7 numbers to a joint the URDF declares fixed (as collections do), and
  // naming a joint the robot lacks.
  const Robot robot = ParseRobot(R"(<robot name="m">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="mount" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="turn" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)",
                                 "m.urdf", "");
  const Srdf s = ParseSrdf(R"(<robot name="m">
  <group_state name="p" group="all"><joint name="mount" value="0 0 0 0 0 0 1"/>
    <joint name="turn" value="0.2"/><joint name="nope" value="1"/></group_state>
</robot>)",
                           "p.srdf");
  const std::vector<std::string> checked = CheckSrdf(s, robot);
  ASSERT_EQ(checked.size(), 1u);
  EXPECT_THAT(checked[0], HasSubstr("joint 'nope'"));
  std::vector<std::string> warnings;
  EXPECT_DOUBLE_EQ(NamedPose(robot, s, "p", &warnings)[0], 0.2);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("p.srdf:2: group_state 'p' joint 'mount' is fixed"));
  // Without a warnings list (a planner's start), the values are an error.
  EXPECT_THAT(Message([&] { NamedPose(robot, s, "p"); }), HasSubstr("value= has 7 numbers"));
}

// ---- URDF limits (issue 16)
// ----------------------------------------------------------------------

TEST(UrdfLimits, DeepNestingIsRefusedBeforeParsing) {
  std::string xml = "<robot name=\"deep\">\n<link name=\"a\">";
  for (int i = 0; i < 100000; ++i) xml += "<x>";
  const std::string m = Message([&] { ParseRobot(xml, "deep.urdf", ""); });
  EXPECT_THAT(m, HasSubstr("deep.urdf:2: XML elements nested deeper than 100 levels"));
  // Comments and quoted '>' do not confuse the scan.
  EXPECT_NO_THROW(
      ParseRobot("<robot name=\"c\"><!-- <a><b> --><link name=\"a>b\"/></robot>", "c.urdf", ""));
}

TEST(UrdfLimits, LongChainLoads) {
  std::string xml = "<robot name=\"long\">\n";
  const int n = 10000;
  for (int i = 0; i < n; ++i) xml += "<link name=\"l" + std::to_string(i) + "\"/>\n";
  for (int i = 1; i < n; ++i) {
    xml += "<joint name=\"j" + std::to_string(i) + "\" type=\"continuous\"><parent link=\"l" +
           std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) +
           "\"/><axis xyz=\"0 0 1\"/></joint>\n";
  }
  xml += "</robot>\n";
  const Robot robot = ParseRobot(xml, "long.urdf", "");
  EXPECT_EQ(robot.links.size(), static_cast<size_t>(n));
  EXPECT_EQ(num_dofs(robot), n - 1);
  // A cycle below the root is still found.
  std::string cyc =
      "<robot name=\"c\"><link name=\"r\"/><link name=\"a\"/><link name=\"b\"/>"
      "<joint name=\"j1\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>"
      "<joint name=\"j2\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint>"
      "</robot>";
  EXPECT_THAT(Message([&] { ParseRobot(cyc, "c.urdf", ""); }), HasSubstr("kinematic cycle"));
}

TEST(UrdfLimits, GeometryUrdfdomWouldDropIsAnError) {
  auto robot_with = [](const std::string& geometry) {
    return "<robot name=\"g\">\n<link name=\"a\">\n<collision name=\"c\">\n<geometry>\n" +
           geometry + "\n</geometry></collision></link></robot>";
  };
  EXPECT_THAT(Message([&] { ParseRobot(robot_with("<box size=\"0.2 0.2 abc\"/>"), "g.urdf", ""); }),
              HasSubstr("g.urdf:5: link 'a' collision 0: <box size=\"0.2 0.2 abc\">: expected 3 "
                        "finite numbers"));
  EXPECT_THAT(Message([&] { ParseRobot(robot_with("<sphere radius=\"1e400\"/>"), "g.urdf", ""); }),
              HasSubstr("expected a finite number"));
  EXPECT_THAT(Message([&] { ParseRobot(robot_with("<capsule radius=\"1\"/>"), "g.urdf", ""); }),
              HasSubstr("unknown geometry <capsule>"));
  EXPECT_THAT(Message([&] { ParseRobot(robot_with(""), "g.urdf", ""); }),
              HasSubstr("<geometry> is empty"));
  const std::string neg =
      "<robot name=\"g\"><link name=\"a\"><collision name=\"capsule_x\"><geometry>"
      "<cylinder radius=\"-0.1\" length=\"1\"/></geometry></collision></link></robot>";
  EXPECT_THAT(Message([&] { ParseRobot(neg, "g.urdf", ""); }),
              HasSubstr("a capsule needs a radius > 0"));
  Geometry cap;
  cap.kind = Geometry::Kind::kCapsule;
  cap.size = Eigen::Vector3d(-0.1, 1.0, 0.0);
  EXPECT_THROW(MakePrimitiveObject("c", cap), std::invalid_argument);
}

TEST(UrdfLimits, PackageUriStaysInsideItsPackage) {
  const std::string base = TestDataFile("fake_pkg/urdf");
  auto with_mesh = [](const std::string& uri) {
    return "<robot name=\"p\"><link name=\"a\"><collision><geometry><mesh filename=\"" + uri +
           "\"/></geometry></collision></link></robot>";
  };
  EXPECT_NO_THROW(ParseRobot(with_mesh("package://fake_pkg/meshes/box.stl"), "p.urdf", base));
  EXPECT_THAT(Message([&] {
                ParseRobot(with_mesh("package://fake_pkg/../../../../../../etc/passwd"), "p.urdf",
                           base);
              }),
              HasSubstr("leaves its package 'fake_pkg'"));
  // Inside the package after normalisation: allowed.
  EXPECT_NO_THROW(
      ParseRobot(with_mesh("package://fake_pkg/urdf/../meshes/box.stl"), "p.urdf", base));
  // The package exists but not the file: the message names the file tried.
  const std::string m =
      Message([&] { ParseRobot(with_mesh("package://fake_pkg/meshes/nope.stl"), "p.urdf", base); });
  EXPECT_THAT(m, HasSubstr("no file "));
  EXPECT_THAT(m, HasSubstr("fake_pkg/meshes/nope.stl"));
  EXPECT_THAT(m, ::testing::Not(HasSubstr("no package")));
}

}  // namespace
}  // namespace planning
