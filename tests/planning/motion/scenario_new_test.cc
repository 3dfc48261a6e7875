// `scenario new` (MakeNewScenario): for robots the project does not ship — made here from
// published dimensions (a UR5-like 6-DOF arm, the same with limits that exclude zero, a
// Panda-like 7-DOF arm with a prismatic two-finger gripper) — and for tinyarm, the written
// scenario loads, and AICO and BiRRT take the hand chain through the ring with no edits.
#include "planning/motion/scenario_new.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/success.h"

namespace planning {
namespace {

namespace fs = std::filesystem;

std::string TempFile(const std::string& name, const std::string& text) {
  // One folder per test: ctest runs the tests as parallel processes, and FindSrdf reads every SRDF
  // next to a URDF (another test's half-written one would be an error).
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "scenario_new_test_tmp" /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
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

// A 7-DOF arm with the Franka Panda's published kinematics (joint origins and limits of its
// datasheet: d1 0.333, d3 0.316, a4 0.0825, a5 −0.0825, d5 0.384, a7 0.088, flange 0.107 m;
// joint 4 in [−3.0718, −0.0698], so zero lies outside its limits) and a prismatic two-finger
// gripper (0–0.04 m each); links as spheres of radius 0.045 at the joint frames.
std::string PandaLikeArm(bool bodies = false) {
  struct J {
    const char* xyz;
    const char* rpy;
    double lo, hi;
  };
  const J joints[7] = {{"0 0 0.333", "0 0 0", -2.8973, 2.8973},
                       {"0 0 0", "-1.5707963 0 0", -1.7628, 1.7628},
                       {"0 -0.316 0", "1.5707963 0 0", -2.8973, 2.8973},
                       {"0.0825 0 0", "1.5707963 0 0", -3.0718, -0.0698},
                       {"-0.0825 0.384 0", "-1.5707963 0 0", -2.8973, 2.8973},
                       {"0 0 0", "1.5707963 0 0", -0.0175, 3.7525},
                       {"0.088 0 0", "1.5707963 0 0", -2.8973, 2.8973}};
  // Each link: a sphere (radius 0.045 m, 0.06 m at the base) at its origin; with `bodies`, more
  // spheres at most 0.04 m apart up to the next joint, so that the body covers the segment
  // between the joint origins (without, a pole fits between two joints).
  const auto link = [&](int i, const char* next) {
    double x = 0, y = 0, z = 0;
    std::sscanf(next, "%lf %lf %lf", &x, &y, &z);
    const int steps = bodies ? 1 + static_cast<int>(std::sqrt(x * x + y * y + z * z) / 0.04) : 0;
    std::string l = "<link name=\"l" + std::to_string(i) + "\">";
    for (int k = 0; k <= steps; ++k) {
      const double t = steps == 0 ? 0.0 : static_cast<double>(k) / steps;
      l.append("<collision><origin xyz=\"" + std::to_string(t * x) + " " + std::to_string(t * y) +
               " " + std::to_string(t * z) + "\"/><geometry><sphere radius=\"" +
               (i == 0 ? "0.06" : "0.045") + "\"/></geometry></collision>");
    }
    return l + "</link>\n";
  };
  std::string u = "<robot name=\"pandalike\">\n" + link(0, joints[0].xyz);
  for (int i = 0; i < 7; ++i) {
    const std::string n = std::to_string(i + 1), parent = std::to_string(i);
    u.append(link(i + 1, i < 6 ? joints[i + 1].xyz : "0 0 0.107"));
    u.append("<joint name=\"j").append(n);
    u.append("\" type=\"revolute\"><parent link=\"l").append(parent).append("\"/><child link=");
    u.append("\"l").append(n).append("\"/><origin xyz=\"").append(joints[i].xyz);
    u.append("\" rpy=\"").append(joints[i].rpy).append("\"/><axis xyz=\"0 0 1\"/><limit ");
    u.append("lower=\"").append(std::to_string(joints[i].lo)).append("\" upper=\"");
    u.append(std::to_string(joints[i].hi)).append("\" effort=\"1\" velocity=\"1\"/></joint>\n");
  }
  u.append("<link name=\"hand\"><collision><origin xyz=\"0 0 0.03\"/><geometry><box size=\"0.05 ");
  u.append("0.18 0.05\"/></geometry></collision></link>\n<joint name=\"hand_joint\" type=\"fixed");
  u.append("\"><parent link=\"l7\"/><child link=\"hand\"/><origin xyz=\"0 0 0.107\" rpy=\"0 0 ");
  u.append("-0.7853982\"/></joint>\n");
  for (const char* side : {"left", "right"}) {
    const bool left = side[0] == 'l';
    u.append("<link name=\"finger_").append(side).append("\"><collision><origin xyz=\"0 ");
    u.append(left ? "0.01" : "-0.01").append(" 0.025\"/><geometry><box size=\"0.02 0.015 0.05\"/>");
    u.append("</geometry></collision></link>\n<joint name=\"finger_").append(side);
    u.append("_joint\" type=\"prismatic\"><parent link=\"hand\"/><child link=\"finger_");
    u.append(side).append("\"/><origin xyz=\"0 0 0.0584\"/><axis xyz=\"0 ");
    u.append(left ? "1" : "-1").append(" 0\"/><limit lower=\"0\" upper=\"0.04\" effort=\"1\" ");
    u.append("velocity=\"1\"/></joint>\n");
  }
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
  ExpectPlans(TempFile("urlike.urdf", UrLikeArm(-3.1)), "urlike", true);
}

TEST(ScenarioNew, ArmWhoseLimitsExcludeZero) {
  ExpectPlans(TempFile("urlike_offzero.urdf", UrLikeArm(0.3)), "urlike_offzero", true);
}

TEST(ScenarioNew, PandaLikeArmWithAPrismaticGripper) {
  ExpectPlans(TempFile("pandalike.urdf", PandaLikeArm()), "pandalike", true);
}

// `--task unwrap`: the start is hooked around the pole (|total writhe| ≥ 0.15), the written
// scenario loads, and AICO and BiRRT unwrap it (success: writhe below 0.05, reach, winding).
void ExpectUnwraps(const std::string& urdf, const std::string& name, bool aico_too = true) {
  NewScenarioOptions o;
  o.task = "unwrap";
  const NewScenario made = MakeNewScenario(urdf, o);
  EXPECT_EQ(made.json["success"]["writhe_total_below"], 0.05);
  const std::string path = TempFile(name + "_unwrap.json", made.json.dump(2));
  const auto s = LoadScenario(path);
  std::vector<Planner> planners = {Planner::kBiRrt};
  if (aico_too) planners.push_back(Planner::kAico);
  for (Planner p : planners) {
    const PlanResult r = RunPlanner(*s, p, 0);
    EXPECT_GE(std::abs(r.report.start_writhe_total), 0.15) << name;
    EXPECT_TRUE(r.report.success) << name << " " << PlannerName(p) << ": "
                                  << FailureReasonName(r.report.failure_reason) << " "
                                  << r.report.failure_detail;
    EXPECT_LT(std::abs(r.report.final_writhe_total), 0.05) << name << " " << PlannerName(p);
  }
}

TEST(ScenarioNew, UnwrapShippedLwr) {
  ExpectUnwraps(TOPOPLAN_SOURCE_DIR "/assets/robots/lwr4_sdh.urdf", "lwr");
}

// AICO unwraps the UR-like arm; on the arm whose limits exclude zero and on the Panda-like arm
// (with bodies between its joints, so that a pole cannot pass between two of them) it ends with a
// joint past its limit (the limit task is a soft cost), which docs/own-robot.md reports; the
// BiRRT unwraps all three.
TEST(ScenarioNew, UnwrapRobotsFromPublishedDimensions) {
  ExpectUnwraps(TempFile("urlike_u.urdf", UrLikeArm(-3.1)), "urlike");
  ExpectUnwraps(TempFile("urlike_offzero_u.urdf", UrLikeArm(0.3)), "urlike_offzero", false);
  ExpectUnwraps(TempFile("pandalike_u.urdf", PandaLikeArm(true)), "pandalike", false);
}

// final_pose without "init" runs inverse kinematics of the reach target (init "ik", the default):
// the goal meets the end conditions (the tool inside the box) and the plan succeeds as with the
// written IK goal.
TEST(ScenarioNew, FinalPoseWithoutInitUsesInverseKinematics) {
  NewScenarioOptions o;
  o.task = "reach";
  NewScenario made = MakeNewScenario(TempFile("urlike_ik.urdf", UrLikeArm(-3.1)), o);
  made.json["final_pose"].erase("init");
  const auto s = LoadScenario(TempFile("urlike_ik.json", made.json.dump(2)));
  EXPECT_EQ(s->spec.final_pose.init, FinalPoseInit::kIk);
  const EndState end = CheckEndState(*s, s->goal_q, true);
  EXPECT_EQ(end.violation, 0.0);  // inside the box, within the limits, collision-free
  EXPECT_GT((s->goal_q - s->initial.problem.q0).norm(), 0.1);
  const PlanResult r = RunPlanner(*s, Planner::kBiRrt, 0);
  EXPECT_TRUE(r.report.success) << FailureReasonName(r.report.failure_reason);
}

TEST(ScenarioNew, UnwrapIsDeterministicPerSeed) {
  NewScenarioOptions o;
  o.task = "unwrap";
  const std::string urdf = TempFile("urlike_seed.urdf", UrLikeArm(-3.1));
  const NewScenario a = MakeNewScenario(urdf, o), b = MakeNewScenario(urdf, o);
  EXPECT_EQ(a.json.dump(), b.json.dump());
  o.seed = 7;
  EXPECT_NE(MakeNewScenario(urdf, o).json["start"].dump(), a.json["start"].dump());
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

// Two UR-like arms on a torso (the tree branches at the root, as on a humanoid or a mobile
// manipulator): with an SRDF, the hand is the parent link of its first end_effector that is not a
// foot; --hand picks the other arm. The other arm's joints are frozen, and the plan succeeds.
std::string TwoArmRobot() {
  std::string u = "<robot name=\"twoarm\">\n<link name=\"torso\"/>\n";
  for (const std::string side : {"left", "right"}) {
    std::string arm = UrLikeArm(-3.1);
    arm = arm.substr(arm.find('\n') + 1);
    arm = arm.substr(0, arm.rfind("</robot>"));
    const std::string prefix = side + "_";
    for (const std::string key : {"name=\"", "link=\""}) {
      for (size_t at = arm.find(key); at != std::string::npos; at = arm.find(key, at + 1)) {
        arm.insert(at + key.size(), prefix);
      }
    }
    u.append(arm);
    u.append("<joint name=\"").append(prefix).append("mount\" type=\"fixed\"><parent link=");
    u.append("\"torso\"/><child link=\"").append(prefix).append("base\"/><origin xyz=\"0 ");
    u.append(side == "left" ? "0.6" : "-0.6").append(" 0\"/></joint>\n");
  }
  return u.append("</robot>\n");
}

TEST(ScenarioNew, TwoArmRobotTakesItsHandFromTheSrdfOrHand) {
  const std::string urdf = TempFile("twoarm.urdf", TwoArmRobot());
  TempFile("twoarm.srdf",
           "<robot name=\"twoarm\">\n"
           "  <end_effector name=\"left_foot\" parent_link=\"torso\" group=\"left_leg\"/>\n"
           "  <end_effector name=\"gripper\" parent_link=\"nowhere\" group=\"arm\"/>\n"
           "  <end_effector name=\"right_hand\" parent_link=\"right_flange\" group=\"arm\"/>\n"
           "</robot>\n");
  const NewScenario made = MakeNewScenario(urdf, {});
  EXPECT_EQ(made.hand_link, "right_flange");
  const nlohmann::ordered_json& frozen = made.json["frozen_joints"];
  EXPECT_EQ(frozen.size(), 6u) << frozen.dump();
  EXPECT_NE(frozen.dump().find("left_j1"), std::string::npos) << frozen.dump();
  const auto s = LoadScenario(TempFile("twoarm_ring.json", made.json.dump(2)));
  for (Planner p : {Planner::kBiRrt, Planner::kAico}) {
    const PlanResult r = RunPlanner(*s, p, 0);
    EXPECT_TRUE(r.report.success) << PlannerName(p) << ": "
                                  << FailureReasonName(r.report.failure_reason) << " "
                                  << r.report.failure_detail;
  }
  NewScenarioOptions left;
  left.hand = "left_flange";
  const NewScenario other = MakeNewScenario(urdf, left);
  EXPECT_EQ(other.hand_link, "left_flange");
  EXPECT_NE(other.json["frozen_joints"].dump().find("right_j6"), std::string::npos);
  // Without an SRDF (another robot name, so none is found): the first of the two arms.
  std::string plain = TwoArmRobot();
  plain.replace(plain.find("twoarm"), 6, "twoarm_plain");
  const NewScenario first = MakeNewScenario(TempFile("twoarm_plain.urdf", plain), {});
  EXPECT_EQ(first.hand_link, "left_l6");  // the last moving link (the flange is fixed)
  NewScenarioOptions bad;
  bad.hand = "no_such_link";
  EXPECT_THROW(MakeNewScenario(urdf, bad), std::invalid_argument);
}

}  // namespace
}  // namespace planning
