// The success criterion every planner is judged by (JudgePlan, planner.h): a path that tunnels
// through the pole between time slices is rejected with `tunnelled`, a 0.1 m miss of the target
// with `reach_error`, an exact hit passes; the winding keys of "success" are checked on load.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "base/str_cat.h"
#include "planning/features/feature.h"
#include "planning/motion/planner.h"
#include "planning/motion/report.h"
#include "planning/motion/scenario.h"
#include "planning/motion/scenario_spec.h"
#include "planning/motion/unwrap_benchmark.h"
#include "planning/motion/unwrap_geometry.h"
#include "planning/robot/kinematics.h"
#include "scenario_test_util.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";

std::string WriteTemp(const std::string& name, const std::string& text) {
  return WriteTestFile("success_test_tmp", name, text);
}

// The shipped unwrap scenario from `wrap_deg`.
std::unique_ptr<Scenario> Unwrap(double wrap_deg) {
  ScenarioOverrides o;
  o.start_wrap_deg = wrap_deg;
  return LoadScenario(kAssets + "scenarios/unwrap.json", o);
}

// Two slices: the start of `coiled` and the unwrapped start (0°). Straight-line interpolation in
// joint space pulls the arm through the pole instead of around its end.
Trajectory PullStraight(const Scenario& coiled) {
  Trajectory path;
  path.q.resize(coiled.initial.problem.q0.size(), 2);
  path.q.col(0) = coiled.initial.problem.q0;
  path.q.col(1) = Unwrap(0.0)->initial.problem.q0;
  return path;
}

TEST(JudgePlan, APathThatTunnelsThroughThePoleBetweenSlicesIsRejected) {
  const auto s = Unwrap(360.0);
  // Judged without the collision checker, so that only the winding criterion can see the arm
  // passing through the pole (as it cannot when the pass falls between resampled states).
  s->collision.self_collision = false;
  s->collision.environment = false;
  const Trajectory path = PullStraight(*s);
  EXPECT_NEAR(std::abs(ReportWinding(*s, path.q.col(0))), 1.0, 0.2);
  EXPECT_LT(std::abs(ReportWinding(*s, path.q.col(1))), 0.2);
  const PlanVerdict v = JudgePlan(*s, path);
  EXPECT_EQ(v.reason, FailureReason::kTunnelled) << FailureReasonName(v.reason);
  EXPECT_GT(v.step, 0);
  EXPECT_GT(v.max_winding_jump_turns, 0.5);  // a whole turn lost in one resampled step
  // The pass is located on the pole: tunnelling with either rule.
  EXPECT_GE(v.winding_jumps.through_object, 1);
  EXPECT_EQ(v.winding_jumps.beyond_ends, 0);
  SuccessCriteria object_rule = s->success;
  object_rule.winding_tunnel_through_object_only = true;
  EXPECT_EQ(JudgePlan(*s, s->initial, path, object_rule).reason, FailureReason::kTunnelled);
}

// The same pass with the report object moved along its own line, beyond the place where the arm
// passes it (the line, and so every winding, unchanged): a pass round the object's end. The shipped
// rule ("tunnel": "line") still calls it tunnelling; "object" does not.
TEST(JudgePlan, APassBeyondTheObjectsEndIsTunnellingOnlyByTheLineRule) {
  const auto s = Unwrap(360.0);
  s->collision.self_collision = false;
  s->collision.environment = false;
  const Trajectory path = PullStraight(*s);
  const auto moved = MakeScenarioState(*s);
  const Eigen::Matrix3Xd pole = moved->report_object_chain;
  ASSERT_EQ(pole.cols(), 2);
  const Eigen::Vector3d along = pole.col(1) - pole.col(0);
  // Both ends moved past the far end by half and one and a half pole lengths.
  moved->report_object_chain.col(0) = pole.col(1) + 0.5 * along;
  moved->report_object_chain.col(1) = pole.col(1) + 1.5 * along;
  const PlanVerdict line = JudgePlan(*s, *moved, path, s->success);
  EXPECT_EQ(line.reason, FailureReason::kTunnelled) << FailureReasonName(line.reason);
  EXPECT_EQ(line.winding_jumps.through_object, 0);
  EXPECT_GE(line.winding_jumps.beyond_ends, 1);
  EXPECT_EQ(line.winding_jumps.unlocated, 0);
  SuccessCriteria object_rule = s->success;
  object_rule.winding_tunnel_through_object_only = true;
  const PlanVerdict object = JudgePlan(*s, *moved, path, object_rule);
  EXPECT_NE(object.reason, FailureReason::kTunnelled) << FailureReasonName(object.reason);
  EXPECT_EQ(object.winding_jumps.beyond_ends, line.winding_jumps.beyond_ends);
  EXPECT_DOUBLE_EQ(object.max_winding_jump_turns, line.max_winding_jump_turns);
}

// The located jumps reach the planner's report, report.json and geometry.csv: AICO without the
// writhe term at 540° pulls the arm through the pole (docs/results/unwrap.md), and a report with
// three distinct counts keeps each in its own field and column.
TEST(JudgePlan, WindingJumpCountsReachTheReportJsonAndGeometryCsv) {
  const auto s = Unwrap(540.0);
  const PlanReport tunnel = RunPlanner(*s, Planner::kAicoGoal, 0).report;
  EXPECT_EQ(tunnel.failure_reason, FailureReason::kTunnelled)
      << FailureReasonName(tunnel.failure_reason);
  EXPECT_GE(tunnel.winding_jumps.through_object, 1);
  EXPECT_EQ(PlanReportJson(*s, tunnel, 0)["winding_jumps"]["through_object"].get<int>(),
            tunnel.winding_jumps.through_object);

  PlanReport r;
  r.winding_jumps.through_object = 3;
  r.winding_jumps.beyond_ends = 5;
  r.winding_jumps.unlocated = 7;
  const nlohmann::json j = PlanReportJson(*s, r, 0)["winding_jumps"];
  EXPECT_EQ(j["through_object"].get<int>(), 3);
  EXPECT_EQ(j["beyond_ends"].get<int>(), 5);
  EXPECT_EQ(j["unlocated"].get<int>(), 7);
  UnwrapGeometry geometry;
  geometry.name = "g";
  UnwrapBenchmarkResult result;
  result.runs.resize(1);
  result.runs[0].report = r;
  std::istringstream csv(UnwrapGeometryCsv(geometry, result));
  std::string header, row;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row));
  const auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::istringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    return cells;
  };
  const std::vector<std::string> names = split(header), cells = split(row);
  ASSERT_EQ(names.size(), cells.size());
  std::map<std::string, std::string> by_name;
  for (size_t i = 0; i < names.size(); ++i) by_name[names[i]] = cells[i];
  EXPECT_EQ(by_name["jumps_through_object"], "3");
  EXPECT_EQ(by_name["jumps_beyond_ends"], "5");
  EXPECT_EQ(by_name["jumps_unlocated"], "7");
}

// With the collision checker on, the resampled states inside the pole collide, but the verdict
// names the cause: the winding jump (tunnelled), not the collision.
TEST(JudgePlan, TunnellingIsNamedBeforeTheCollisionOnTheWayThrough) {
  const auto s = Unwrap(360.0);
  const PlanVerdict v = JudgePlan(*s, PullStraight(*s));
  EXPECT_FALSE(v.collision_free);
  EXPECT_EQ(v.reason, FailureReason::kTunnelled) << FailureReasonName(v.reason);
  EXPECT_GT(v.step, 0);
  EXPECT_GT(v.max_winding_jump_turns, 0.5);
}

// A 7-dof arm whose link-7 origin must reach `target`; the path is the single state q = 0.
std::unique_ptr<Scenario> ReachScenario(const std::string& name, double miss_m) {
  const std::string robot = R"({"robot": ")" + kAssets + R"(robots/lwr4_sdh.urdf",
      "start": {"q": "zero"}, "problem": {"T": 5}, )";
  const auto probe = LoadScenario(
      WriteTemp("probe.json", robot + R"("tasks": [{"feature": {"type": "joint_position"}}]})"));
  KinematicsData kin(probe->robot);
  ForwardKinematics(probe->robot, probe->initial.problem.q0, &kin);
  const int link = FindLink(probe->robot, "lwr_link_7");
  const Eigen::Vector3d p = kin.world_from_link[link].translation() + Eigen::Vector3d(miss_m, 0, 0);
  char target[160];
  std::snprintf(target, sizeof(target), "[%.17g, %.17g, %.17g]", p.x(), p.y(), p.z());
  return LoadScenario(WriteTemp(name, robot + R"("tasks": [{"name": "reach",
      "feature": {"type": "position", "link": "lwr_link_7"}, "target": {"value": )" +
                                          target +
                                          R"(}}],
      "success": {"position": {"task": "reach", "tolerance": 0.05}}})"));
}

TEST(JudgePlan, TheReachCriterionRejectsATenCentimetreMiss) {
  for (const double miss : {0.0, 0.1}) {
    const auto s = ReachScenario("reach.json", miss);
    Trajectory path;
    path.q = s->initial.problem.q0;
    const PlanVerdict v = JudgePlan(*s, path);
    SCOPED_TRACE("miss " + std::to_string(miss));
    EXPECT_NEAR(v.reach_error_m, miss, 1e-5);
    EXPECT_EQ(v.reason, miss > 0.05 ? FailureReason::kReachError : FailureReason::kNone)
        << FailureReasonName(v.reason);
  }
}

TEST(JudgePlan, WindingCriterionNeedsAReportPairAndPositiveBounds) {
  const std::string base = R"({"robot": ")" + kAssets + R"(robots/lwr4_sdh.urdf",
      "start": {"q": "zero"}, "tasks": [{"feature": {"type": "joint_position"}}], "success": )";
  for (const auto& [success, fragment] :
       {std::pair<std::string, std::string>{R"({"winding": {}})", "needs writhe_report"},
        {R"({"winding": {"max_jump": 0}})", "must be > 0"},
        {R"({"winding": {"jump": 0.1}})", "unknown key"}}) {
    try {
      LoadScenario(WriteTemp("winding.json", base + success + "}"));
      ADD_FAILURE() << "expected an error for " << success;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("success.winding"), std::string::npos) << e.what();
    }
  }
}

// "final_closure": "chord" judges the loop the arm makes with its chord (last point back to the
// first): its winding about the pole's line is a whole number of turns (±2 for the coil at 720°,
// 0 unwrapped), where the open chain's is not. With the pole tilted by 20° the set-up's goal (the
// arm unwrapped at the target) winds about a third of a turn about the moved line, so the open
// criterion calls it wrapped; closed by its chord it winds 0 and meets the winding condition.
TEST(JudgePlan, ChordClosureCountsWholeTurnsAboutThePole) {
  for (const double wrap : {0.0, 360.0, 720.0}) {
    const auto s = Unwrap(wrap);
    SuccessCriteria open = s->success, chord = s->success;
    chord.winding_closed_by_chord = true;
    const Eigen::VectorXd q0 = s->initial.problem.q0;
    const double w_open = CheckEndState(*s, s->initial, q0, false, open).winding_turns;
    const double w_chord = CheckEndState(*s, s->initial, q0, false, chord).winding_turns;
    SCOPED_TRACE("wrap " + std::to_string(wrap));
    EXPECT_NEAR(w_chord, std::round(w_chord), 1e-9);
    EXPECT_NEAR(std::abs(w_chord), std::round(wrap / 360.0), 1e-9);
    EXPECT_NEAR(w_open, w_chord, 0.25);  // the chord winds less than a quarter turn
  }
  ScenarioSpec spec = ParseScenarioSpec(kAssets + "scenarios/unwrap.json");
  UnwrapGeometry g;
  g.pole_tilt_deg = Eigen::Vector2d(20.0, 0.0);
  ApplyUnwrapGeometry(g, &spec);
  const auto s = SetUpScenario(spec, 0.0);
  Trajectory still;  // the set-up's goal q̂_T, unwrapped at the target
  still.q = s->goal_q;
  SuccessCriteria open = s->success, chord = s->success;
  chord.winding_closed_by_chord = true;
  const PlanVerdict v_open = JudgePlan(*s, s->initial, still, open);
  const PlanVerdict v_chord = JudgePlan(*s, s->initial, still, chord);
  EXPECT_GE(std::abs(v_open.final_winding_turns), s->success.winding_final_below);
  EXPECT_NEAR(v_chord.final_winding_turns, 0.0, 1e-9);
  EXPECT_FALSE(CheckEndState(*s, s->initial, still.q, false, open).writhe_reached);
  EXPECT_TRUE(CheckEndState(*s, s->initial, still.q, false, chord).writhe_reached);
}

// The closure key: "open" (the default) or "chord"; anything else names the key.
// The path of a copy of the shipped unwrap.json with `key` ("name": "value") added to its
// success.winding object.
std::string UnwrapWithWindingKey(const std::string& name, const std::string& value) {
  std::ifstream in(kAssets + "scenarios/unwrap.json");
  std::string text(std::istreambuf_iterator<char>(in), {});
  const std::string anchor = R"("final_below": 0.1)";
  const size_t at = text.find(anchor);
  EXPECT_NE(at, std::string::npos);
  text.insert(at + anchor.size(), base::StrCat(", \"", name, "\": \"", value, "\""));
  return WriteTemp(name + "_" + value + ".json", text);
}

// ParseScenarioSpec of `path` throws std::invalid_argument naming `where`.
void ExpectSpecErrorNaming(const std::string& path, const std::string& where) {
  try {
    ParseScenarioSpec(path, {kAssets});
    ADD_FAILURE() << "expected an error naming " << where;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
  }
}

TEST(JudgePlan, ChordClosureKeyIsChecked) {
  EXPECT_TRUE(ParseScenarioSpec(UnwrapWithWindingKey("final_closure", "chord"), {kAssets})
                  .success.winding_closed_by_chord);
  ExpectSpecErrorNaming(UnwrapWithWindingKey("final_closure", "loop"),
                        "success.winding.final_closure");
  EXPECT_FALSE(
      ParseScenarioSpec(kAssets + "scenarios/unwrap.json").success.winding_closed_by_chord);
}

TEST(JudgePlan, TunnelRuleKeyIsChecked) {
  for (const std::string rule : {"object", "line"}) {
    const std::string path = UnwrapWithWindingKey("tunnel", rule);
    EXPECT_EQ(ParseScenarioSpec(path, {kAssets}).success.winding_tunnel_through_object_only,
              rule == "object");
    ScenarioOverrides o;
    o.search_roots = {kAssets};
    o.start_wrap_deg = 0.0;
    EXPECT_EQ(LoadScenario(path, o)->success.winding_tunnel_through_object_only, rule == "object");
  }
  ExpectSpecErrorNaming(UnwrapWithWindingKey("tunnel", "pole"), "success.winding.tunnel");
  EXPECT_FALSE(ParseScenarioSpec(kAssets + "scenarios/unwrap.json")
                   .success.winding_tunnel_through_object_only);
}

// The goal q̂_T (the RRT baselines' goal, the end of AICO's final-pose targets) meets the same end
// conditions as a successful plan: within the limits, collision-free, |writhe| < 0.05, winding
// near 0, grasp point within 0.05 m of the cylinder.
TEST(FinalPoseGoal, MeetsTheEndConditionsOfTheSuccessCriterion) {
  for (const double wrap : {90.0, 360.0, 720.0, 1080.0}) {
    const auto s = Unwrap(wrap);
    SCOPED_TRACE("start wrap " + std::to_string(wrap));
    const EndState e = CheckEndState(*s, s->goal_q, true);
    EXPECT_TRUE(e.within_limits);
    EXPECT_TRUE(e.collision_free);
    EXPECT_LT(std::abs(e.writhe_total), 0.05);
    EXPECT_LT(std::abs(e.winding_turns), 0.1);
    EXPECT_GE(e.reach_error_m, 0.0);
    EXPECT_LE(e.reach_error_m, 0.05);
    EXPECT_TRUE(e.ok());
    EXPECT_EQ(e.violation, 0.0);
    std::printf("GOAL wrap %g reach %g writhe %g winding %g\n", wrap, e.reach_error_m,
                e.writhe_total, e.winding_turns);
    // The JudgePlan verdict of the one-state path at the goal agrees.
    Trajectory at_goal;
    at_goal.q = s->goal_q;
    EXPECT_EQ(JudgePlan(*s, at_goal).reason, FailureReason::kNone);
  }
}

// The "unwinding" target kind: the shipped unwrap scenario plus a joint-space reference task along
// the unwinding path (the coil continued from q0 to writhe 0, resampled over t = 0..T). That path
// starts at q0, is collision-free and does not tunnel through the pole (JudgePlan on it), and its
// targets are its states.
TEST(UnwindingTarget, FollowsACollisionFreePathWithoutTunnelling) {
  std::ifstream in(kAssets + "scenarios/unwrap.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const std::string dir : {"robots", "objects"}) {
    const std::string from = "\"../" + dir + "/", to = "\"" + kAssets + dir + "/";
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
      text.replace(at, from.size(), to);
  }
  const std::string qdot = R"({"name": "qdot")";
  text.replace(text.find(qdot), 0,
               R"({"name": "unwind", "feature": {"type": "joint_position"},
                   "target": {"type": "unwinding"}, "precision": 10, "final_precision": 0},)");
  ScenarioOverrides o;
  o.start_wrap_deg = 720.0;
  const auto s = LoadScenario(WriteTemp("unwinding.json", text), o);
  const int T = s->initial.problem.num_steps;
  ASSERT_EQ(s->unwinding.cols(), T + 1);
  EXPECT_TRUE(s->unwinding.col(0).isApprox(s->initial.problem.q0));
  EXPECT_LT(std::abs(ReportWritheTotal(*s, s->unwinding.col(T))), 0.05);
  const Task* unwind = nullptr;
  for (const Task& t : s->initial.problem.tasks) {
    if (t.name == "unwind") unwind = &t;
  }
  ASSERT_NE(unwind, nullptr);
  EXPECT_EQ(unwind->target, s->unwinding);
  Trajectory path;
  path.q = s->unwinding;
  const PlanVerdict v = JudgePlan(*s, path);
  EXPECT_TRUE(v.collision_free);
  EXPECT_LT(v.max_winding_jump_turns, 0.1);
  EXPECT_NE(v.reason, FailureReason::kTunnelled);
  EXPECT_NE(v.reason, FailureReason::kCollision);
  // Set up again from the resolved poses (no continuation, no final-pose estimate): the same
  // start, unwinding targets and goal, so the same AICO problem and plan.
  const ResolvedPoses poses = ResolvedPosesOf(*s);
  const auto again =
      SetUpScenario(ParseScenarioSpec(WriteTemp("unwinding.json", text)), {}, &poses);
  EXPECT_EQ(again->initial.problem.q0, s->initial.problem.q0);
  EXPECT_EQ(again->goal_q, s->goal_q);
  EXPECT_EQ(again->unwinding, s->unwinding);
  ASSERT_EQ(again->initial.problem.tasks.size(), s->initial.problem.tasks.size());
  for (size_t i = 0; i < s->initial.problem.tasks.size(); ++i)
    EXPECT_EQ(again->initial.problem.tasks[i].target, s->initial.problem.tasks[i].target) << i;
  // Wrong sizes are refused.
  ResolvedPoses bad = poses;
  bad.unwinding.resize(0, 0);
  EXPECT_THROW(SetUpScenario(ParseScenarioSpec(WriteTemp("unwinding.json", text)), {}, &bad),
               std::invalid_argument);
  // Without a coil start there is no unwinding path.
  try {
    LoadScenario(WriteTemp("unwinding_q.json", R"({"robot": ")" + kAssets +
                                                   R"(robots/lwr4_sdh.urdf", "start": {"q": "zero"},
        "tasks": [{"feature": {"type": "joint_position"}, "target": {"type": "unwinding"}}]})"));
    ADD_FAILURE() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("need a coil start"), std::string::npos) << e.what();
  }
}

TEST(FailureReasons, NamesAreStable) {
  EXPECT_STREQ(FailureReasonName(FailureReason::kTunnelled), "tunnelled");
  EXPECT_STREQ(FailureReasonName(FailureReason::kReachError), "reach_error");
  EXPECT_STREQ(FailureReasonName(FailureReason::kWritheNotReached), "writhe_not_reached");
  EXPECT_STREQ(FailureReasonName(FailureReason::kBudgetExhausted), "budget_exhausted");
}

// A run without a path reports the end quantities of the start it stayed in (not the zeros of an
// unwrapped arm at the target): at 720° the winding about the pole is about −2 turns (the coil),
// the grasp point is far from the cylinder, and the failure is the budget.
TEST(RunPlanner, ARunWithoutAPathReportsTheStartItStayedIn) {
  auto s = Unwrap(720.0);
  s->rrt.max_checks = 50;
  const PlanResult r = RunPlanner(*s, Planner::kBiRrt, 0);
  ASSERT_EQ(r.trajectory.num_points(), 0);
  EXPECT_FALSE(r.report.success);
  EXPECT_EQ(r.report.failure_reason, FailureReason::kBudgetExhausted);
  EXPECT_EQ(r.report.failure_step, -1);
  EXPECT_NEAR(std::abs(r.report.final_winding_turns), 2.0, 0.25);
  EXPECT_NEAR(r.report.final_writhe_total, r.report.start_writhe_total, 1e-12);
  EXPECT_GT(r.report.reach_error_m, 0.5);
  EXPECT_EQ(r.report.max_winding_jump_turns, 0.0);
  EXPECT_GT(r.report.min_clearance_m, 0.0);  // the start coil is collision-free
}

// through_loop: the hand chain must end through the ring. The start pose does not (only that
// criterion is checked here); the AICO plan's end does, through a named segment of the chain.
TEST(JudgePlan, ThroughLoopNeedsTheChainThroughTheRing) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  SuccessCriteria only_loop;
  only_loop.through_loop = true;
  Trajectory start;
  start.q = s->initial.problem.q0;
  const PlanVerdict at_start = JudgePlan(*s, s->initial, start, only_loop);
  EXPECT_TRUE(at_start.loop_checked);
  EXPECT_FALSE(at_start.passed_through);
  EXPECT_EQ(at_start.reason, FailureReason::kNotThroughLoop) << FailureReasonName(at_start.reason);
  EXPECT_STREQ(FailureReasonName(FailureReason::kNotThroughLoop), "not_through_loop");
  const PlanResult plan = RunPlanner(*s, Planner::kAico, 0);
  ASSERT_TRUE(plan.report.success);
  const PlanVerdict at_end = JudgePlan(*s, s->initial, plan.trajectory, only_loop);
  EXPECT_TRUE(at_end.passed_through);
  EXPECT_GE(at_end.through_segment, 0);
  EXPECT_EQ(at_end.reason, FailureReason::kNone) << FailureReasonName(at_end.reason);
  // Without the criterion the verdict still says whether the chain passed (reports use it).
  EXPECT_TRUE(JudgePlan(*s, plan.trajectory).passed_through);
}

// The scenario key: on in reach_through_ring, refused without a report pair.
TEST(JudgePlan, ThroughLoopIsAScenarioCriterion) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  EXPECT_TRUE(s->success.through_loop);
  const std::string base = R"({"robot": ")" + kAssets + R"(robots/lwr4_sdh.urdf",
      "start": {"q": "zero"}, "tasks": [{"feature": {"type": "joint_position"}}], "success": )";
  try {
    LoadScenario(WriteTemp("loop.json", base + R"({"through_loop": true}})"));
    ADD_FAILURE() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("success.through_loop: the through_loop criterion needs "
                                         "writhe_report"),
              std::string::npos)
        << e.what();
  }
}

// A path that leaves the limits is named by its joint, value, range and unit.
TEST(JudgePlan, JointLimitFailureNamesTheJoint) {
  const auto s = LoadScenario(kAssets + "scenarios/tinyarm_ring.json");
  Trajectory path;
  path.q = s->initial.problem.q0;
  path.q(5, 0) = -0.01;  // finger_left_joint, prismatic [0, 0.03]
  const PlanVerdict v = JudgePlan(*s, path);
  EXPECT_EQ(v.reason, FailureReason::kJointLimits);
  EXPECT_EQ(v.step, 0);
  EXPECT_EQ(v.detail, "joint 'finger_left_joint' (q[5]) = -0.01 outside [0, 0.03] m");
}

// Margins by joint type: `margin` [rad] for revolute joints, `prismatic_margin` [m] for prismatic
// ones, each at most 45 % of the range (a 5 cm margin never inverts a 3 cm finger range).
TEST(JointLimitFeature, MarginsFollowTheJointType) {
  const auto s = LoadScenario(kAssets + "scenarios/tinyarm_ring.json");
  const Robot& r = s->robot;
  const auto f = MakeJointLimitFeature(r, 0.05, 0.05);
  KinematicsData kin(r);
  Eigen::VectorXd q = s->initial.problem.q0;
  q[5] = 0.015;  // the middle of the finger's range: inside even with the capped margin
  Eigen::VectorXd y(f->dim());
  ForwardKinematics(r, q, &kin);
  f->Eval(r, kin, nullptr, y, nullptr);
  EXPECT_EQ(y[5], 0.0);
  q[5] = 0.0;  // at the lower limit: 0.45 · 0.03 inside the capped margin
  ForwardKinematics(r, q, &kin);
  f->Eval(r, kin, nullptr, y, nullptr);
  EXPECT_NEAR(y[5], 0.45 * 0.03, 1e-12);
  // Without a prismatic margin the finger at its limit is fine.
  const auto g = MakeJointLimitFeature(r, 0.05);
  g->Eval(r, kin, nullptr, y, nullptr);
  EXPECT_EQ(y[5], 0.0);
}

// "frozen_joints": an SRDF group held at its start value; unknown names list the joints.
TEST(FrozenJoints, AGroupIsHeldAndLeavesQ) {
  std::string text;
  {
    std::ifstream in(kAssets + "scenarios/tinyarm_ring.json");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  // Paths of the shipped file made absolute, so that the copy can live in the build folder.
  for (const std::string from : {"\"../robots/", "\"../objects/"}) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + 1)) {
      text.replace(at, from.size(), "\"" + kAssets + from.substr(4));
    }
  }
  const auto load = [&](const std::string& frozen) {
    std::string t = text;
    t.replace(t.find("\"robot\":"), 0, "\"frozen_joints\": " + frozen + ",\n  ");
    return LoadScenario(WriteTemp("frozen.json", t));
  };
  const auto s = load(R"(["gripper"])");
  EXPECT_EQ(num_dofs(s->robot), 5);
  ASSERT_EQ(s->frozen.size(), 1u);
  EXPECT_EQ(s->frozen[0].first, "finger_left_joint");
  EXPECT_EQ(s->frozen[0].second, 0.0);  // its value in the start pose 'ready'
  EXPECT_EQ(s->initial.problem.q0.size(), 5);
  try {
    load(R"(["thumb"])");
    ADD_FAILURE() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("frozen_joints: 'thumb' is neither a joint of robot "
                                         "'tinyarm' (joint1, joint2, joint3, joint4, joint5, "
                                         "finger_left_joint) nor a group of its SRDF"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace planning
