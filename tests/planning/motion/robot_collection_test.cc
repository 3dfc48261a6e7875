// Walking a robot folder: URDF/SRDF pairing (stem, robot name, nearest folder), rows for broken
// robots and SRDFs without URDF, and the checked poses.
#include "planning/motion/robot_collection.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace planning {
namespace {

namespace fs = std::filesystem;

const char* kUrdf = R"(<robot name="%s">
  <link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="b"><collision><origin xyz="0 0 0.3"/><geometry><sphere radius="0.05"/></geometry>
  </collision></link>
  <link name="c"><collision><origin xyz="0 0 0.3"/><geometry><sphere radius="0.05"/></geometry>
  </collision></link>
  <joint name="j1" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="prismatic"><parent link="a"/><child link="c"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

void Write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

std::string Urdf(const std::string& name) {
  const std::string text = kUrdf;
  const size_t at = text.find("%s");
  std::string s = text.substr(0, at);
  s.append(name);
  s.append(text, at + 2, std::string::npos);
  return s;
}

// b and c are siblings: apart at (0.5, -0.5), overlapping at (0, 0).
std::string Srdf(const std::string& name) {
  std::string s = "<robot name=\"";
  s.append(name).append("\">\n<group_state name=\"apart\" group=\"g\">");
  s.append("<joint name=\"j1\" value=\"0.5\"/><joint name=\"j2\" value=\"-0.5\"/>");
  s.append("</group_state>\n<group_state name=\"together\" group=\"g\">");
  s.append("<joint name=\"j1\" value=\"0\"/><joint name=\"j2\" value=\"0\"/>");
  return s.append("</group_state>\n</robot>\n");
}

TEST(RobotCollection, PairsByStemThenRobotNameInTheNearestFolder) {
  const fs::path root = fs::temp_directory_path() / "topoplan_collection_test";
  fs::remove_all(root);
  // One package for everything (as example-robot-data): two robots share the stem "r".
  Write(root / "package.xml", "<package><name>coll</name></package>");
  Write(root / "robots/a_description/urdf/r.urdf", Urdf("ra"));
  Write(root / "robots/b_description/urdf/r.urdf", Urdf("rb"));
  Write(root / "robots/b_description/srdf/r.srdf", Srdf("rb"));
  // Paired by robot name: the SRDF's stem matches no URDF.
  Write(root / "robots/c_description/urdf/c_robot.urdf", Urdf("cee"));
  Write(root / "robots/c_description/srdf/cee_moveit.srdf", Srdf("cee"));
  Write(root / "robots/d_description/srdf/lonely.srdf", Srdf("nobody"));
  Write(root / "robots/e_description/urdf/broken.urdf", "<robot name=\"x\"><link name=\"a\">");
  Write(root / ".hidden/urdf/skip.urdf", Urdf("hidden"));

  const std::vector<CollectionRobot> robots = FindCollectionRobots(root.string());
  ASSERT_EQ(robots.size(), 5u);
  EXPECT_EQ(fs::path(robots[0].urdf), root / "robots/a_description/urdf/r.urdf");
  EXPECT_EQ(robots[0].srdf, "");
  EXPECT_EQ(fs::path(robots[1].urdf), root / "robots/b_description/urdf/r.urdf");
  EXPECT_EQ(fs::path(robots[1].srdf), root / "robots/b_description/srdf/r.srdf");
  EXPECT_EQ(robots[1].paired_by, "stem");
  EXPECT_EQ(fs::path(robots[2].srdf), root / "robots/c_description/srdf/cee_moveit.srdf");
  EXPECT_EQ(robots[2].paired_by, "robot name");
  EXPECT_EQ(robots[3].urdf, "");  // d: SRDF without URDF
  EXPECT_EQ(fs::path(robots[4].urdf), root / "robots/e_description/urdf/broken.urdf");

  const CollectionRow b = CheckCollectionRobot(robots[1], {});
  ASSERT_EQ(b.status, CollectionStatus::kLoaded);
  EXPECT_EQ(b.name, "rb");
  EXPECT_EQ(b.links, 3);
  EXPECT_EQ(b.dofs, 2);
  ASSERT_EQ(b.poses.size(), 2u);
  EXPECT_EQ(b.poses[0].name, "apart");
  EXPECT_FALSE(b.poses[0].in_collision);
  EXPECT_EQ(b.poses[1].name, "together");
  EXPECT_TRUE(b.poses[1].in_collision);
  ASSERT_EQ(b.poses[1].pairs.size(), 1u);
  EXPECT_EQ(b.poses[1].pairs[0], "b vs c");

  const CollectionRow lonely = CheckCollectionRobot(robots[3], {});
  EXPECT_EQ(lonely.status, CollectionStatus::kNoUrdf);
  const CollectionRow broken = CheckCollectionRobot(robots[4], {});
  EXPECT_EQ(broken.status, CollectionStatus::kRefused);
  EXPECT_NE(broken.reason.find("broken.urdf"), std::string::npos) << broken.reason;

  EXPECT_THROW(FindCollectionRobots((root / "package.xml").string()), std::invalid_argument);
  fs::remove_all(root);
}

}  // namespace
}  // namespace planning
