// `scenario new` (MakeNewScenario): for robots the project does not ship — made here from
// published dimensions — and for tinyarm, the written scenario loads, and a planner takes the hand
// chain through the ring with no edits.
#include "planning/motion/scenario_new.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"

namespace planning {
namespace {

namespace fs = std::filesystem;

std::string TempFile(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "scenario_new_test_tmp";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return (dir / name).string();
}

// A 6-DOF arm with the UR5's published DH lengths (d1 0.089159, a2 0.425, a3 0.39225, d4 0.10915,
// d5 0.09465, d6 0.0823 m), capsule links of radius 0.04; `lower2` is joint 2's lower limit (> 0
// makes a robot whose zero lies outside its limits).
std::string UrLikeArm(double lower2) {
  struct L {
    const char* xyz;
    const char* axis;
    const char* capsule;  // origin of the capsule, its length
    double length;
  };
  const L links[6] = {{"0 0 0.089159", "0 0 1", "0 0 0", 0.0},
                      {"0 0.13585 0", "0 1 0", "0 0 0.2125", 0.425},
                      {"0 -0.1197 0.425", "0 1 0", "0 0 0.196", 0.392},
                      {"0 0 0.39225", "0 1 0", "0 0.05 0", 0.0},
                      {"0 0.093 0", "0 0 1", "0 0 0.05", 0.0},
                      {"0 0 0.09465", "0 1 0", "0 0.04 0", 0.0}};
  std::string u =
      "<robot name=\"urlike\">\n<link name=\"base\"><collision name=\"capsule_b\">"
      "<geometry><cylinder radius=\"0.06\" length=\"0.05\"/></geometry></collision>"
      "</link>\n";
  for (int i = 0; i < 6; ++i) {
    const std::string n = std::to_string(i + 1);
    u.append("<link name=\"l").append(n).append("\"><collision name=\"capsule_").append(n);
    u.append("\"><origin xyz=\"").append(links[i].capsule).append("\"/><geometry><cylinder ");
    u.append("radius=\"0.04\" length=\"").append(std::to_string(links[i].length));
    u.append("\"/></geometry></collision></link>\n");
    u.append("<joint name=\"j").append(n).append("\" type=\"revolute\"><parent link=\"");
    std::string parent = "l";
    parent.append(std::to_string(i));
    u.append(i == 0 ? std::string("base") : parent).append("\"/><child link=\"l").append(n);
    u.append("\"/><origin xyz=\"").append(links[i].xyz).append("\"/><axis xyz=\"");
    u.append(links[i].axis).append("\"/><limit lower=\"");
    u.append(std::to_string(i == 1 ? lower2 : -3.1)).append("\" upper=\"3.1\" effort=\"1\" ");
    u.append("velocity=\"1\"/></joint>\n");
  }
  u.append("<link name=\"flange\"/><joint name=\"flange_joint\" type=\"fixed\"><parent ");
  u.append("link=\"l6\"/><child link=\"flange\"/><origin xyz=\"0 0.0823 0\"/></joint>\n");
  return u.append("</robot>\n");
}

void ExpectPlans(const std::string& urdf, const std::string& name, bool aico_too) {
  NewScenarioOptions o;
  const NewScenario made = MakeNewScenario(urdf, o);
  EXPECT_TRUE(made.json.contains("final_pose"));
  EXPECT_EQ(made.json["success"]["through_loop"], true);
  const std::string path = TempFile(name + ".json", made.json.dump(2));
  const auto s = LoadScenario(path);
  EXPECT_TRUE(s->success.through_loop);
  std::vector<Planner> planners = {Planner::kBiRrt};
  if (aico_too) planners.push_back(Planner::kAico);
  for (Planner p : planners) {
    const PlanResult r = RunPlanner(*s, p, 0);
    EXPECT_TRUE(r.report.success) << name << " " << PlannerName(p) << ": "
                                  << FailureReasonName(r.report.failure_reason) << " "
                                  << r.report.failure_detail;
    EXPECT_TRUE(r.report.passed_through) << name << " " << PlannerName(p);
  }
}

TEST(ScenarioNew, TinyarmRingPlansWithAicoAndBiRrt) {
  ExpectPlans(TOPOPLAN_SOURCE_DIR "/assets/robots/tinyarm/urdf/tinyarm.urdf", "tinyarm", true);
}

TEST(ScenarioNew, UrLikeArmFromPublishedDimensions) {
  ExpectPlans(TempFile("urlike.urdf", UrLikeArm(-3.1)), "urlike", false);
}

TEST(ScenarioNew, ArmWhoseLimitsExcludeZero) {
  ExpectPlans(TempFile("urlike_offzero.urdf", UrLikeArm(0.3)), "urlike_offzero", false);
}

TEST(ScenarioNew, ARobotWithoutAnArmIsRefused) {
  const std::string urdf = TempFile(
      "star.urdf",
      "<robot name=\"star\"><link name=\"c\"/><link name=\"a\"/><link name=\"b\"/>"
      "<joint name=\"ja\" type=\"revolute\"><parent link=\"c\"/><child link=\"a\"/><axis "
      "xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"
      "<joint name=\"jb\" type=\"revolute\"><parent link=\"c\"/><child link=\"b\"/><axis "
      "xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"
      "</robot>");
  try {
    MakeNewScenario(urdf, {});
    ADD_FAILURE() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no arm found"), std::string::npos) << e.what();
  }
  NewScenarioOptions bad;
  bad.task = "unwrap";
  EXPECT_THROW(MakeNewScenario(urdf, bad), std::invalid_argument);
}

}  // namespace
}  // namespace planning
