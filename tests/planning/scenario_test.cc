// Scenario loader errors, and the end-to-end planning properties of the shipped scenarios:
// unwrap from 360° and 720° (AICO: |total writhe| < 0.05, collision-free at the edge
// resolution), reach_through_ring (inside the box, writhe peak at the link through the ring),
// RRT paths collision-free, same seed → same report.
#include "planning/planner.h"
#include "planning/scenario.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "planning/kinematics.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::filesystem::path dir =
      std::filesystem::path(TOPOPLAN_BINARY_DIR) / "scenario_test_tmp";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

// A minimal valid scenario around the LWR4 + SDH; `task` is spliced into "tasks".
std::string MiniScenario(const std::string& task, const std::string& start = "\"zero\"") {
  return R"({"robot": ")" + kAssets + R"(robots/lwr4_sdh.urdf",
    "start": {"q": )" +
         start + R"(}, "problem": {"T": 5},
    "tasks": [)" +
         task + "]}";
}

void ExpectLoadError(const std::string& name, const std::string& text,
                     const std::string& fragment) {
  const std::string path = WriteTemp(name, text);
  try {
    LoadScenario(path);
    FAIL() << "expected an error containing '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(ScenarioLoader, ErrorsNameTheJsonPath) {
  ExpectLoadError("unknown_feature.json",
                  MiniScenario(R"({"name": "x", "feature": {"type": "teleport"}})"),
                  "tasks[0].feature.type");
  ExpectLoadError("bad_size.json",
                  MiniScenario(R"({"name": "x", "feature": {"type":
                  "joint_position"}})",
                               "[0, 1, 2]"),
                  "start.q");
  ExpectLoadError("bad_target.json",
                  MiniScenario(R"({"name": "x", "feature": {"type": "position", "link":
                  "sdh_palm"}, "target": {"type": "value", "value": [1, 2]}})"),
                  "tasks[0].target.value");
  ExpectLoadError("unknown_link.json",
                  MiniScenario(R"({"name": "x", "feature": {"type": "position", "link":
                  "no_such_link"}})"),
                  "tasks[0].feature.link");
  ExpectLoadError("missing_robot.json",
                  R"({"robot": "does/not/exist.urdf", "start": {"q": "zero"}, "tasks": []})",
                  "robot");
  ExpectLoadError("not_json.json", "{ this is not json", "invalid JSON");
  EXPECT_THROW(LoadScenario("/nonexistent/scenario.json"), std::invalid_argument);
}

// One AICO run on unwrap from the given start wrap.
void CheckUnwrap(double wrap_deg) {
  ScenarioOverrides o;
  o.start_wrap_deg = wrap_deg;
  const auto s = LoadScenario(kAssets + "scenarios/unwrap.json", o);
  EXPECT_NEAR(s->start_wrap_deg, wrap_deg, 5.0);
  const PlanResult r = RunPlanner(*s, Planner::kAico, 0);
  SCOPED_TRACE("start wrap " + std::to_string(wrap_deg));
  EXPECT_NEAR(std::abs(r.report.start_writhe_total) * 360.0, wrap_deg, 5.0);
  EXPECT_LT(std::abs(r.report.final_writhe_total), 0.05);
  EXPECT_TRUE(r.report.path_collision_free);
  EXPECT_GT(r.report.min_clearance_m, 0.0);
  EXPECT_EQ(r.trajectory.num_points(), s->problem.num_steps + 1);
  // Accepted sweeps never raise the cost.
  for (size_t k = 1; k < r.report.cost_history.size(); ++k) {
    EXPECT_LE(r.report.cost_history[k], r.report.cost_history[k - 1]);
  }
  EXPECT_GT(r.report.collision_checks, 0);
}

TEST(UnwrapScenario, AicoUnwrapsFrom360Degrees) { CheckUnwrap(360.0); }
TEST(UnwrapScenario, AicoUnwrapsFrom720Degrees) { CheckUnwrap(720.0); }

TEST(ReachThroughRing, AicoEndsInsideTheBoxWithTheWrithePeakAtTheLinkThroughTheRing) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  const PlanResult r = RunPlanner(*s, Planner::kAico, 0);
  EXPECT_TRUE(r.report.success) << StatusName(r.report.status);
  EXPECT_TRUE(r.report.path_collision_free);
  const Eigen::VectorXd q_end = r.trajectory.q.col(r.trajectory.num_points() - 1);
  // Inside the box.
  const Task& box = s->problem.tasks[s->success.box_task];
  KinematicsData kin(s->robot);
  ForwardKinematics(s->robot, q_end, &kin);
  auto data = box.feature->CreateData(s->robot);
  Eigen::VectorXd y(3);
  box.feature->Eval(s->robot, kin, data.get(), y, nullptr);
  EXPECT_LT(y.norm(), 1e-9);
  // The arm passes through the ring: the writhe of arm × ring jumps from ~0 to ~1 in total.
  Eigen::MatrixXd W;
  EXPECT_GT(ReportWritheTotal(*s, q_end, &W), 0.5);
  EXPECT_LT(std::abs(r.report.start_writhe_total), 0.3);
  // Fig. 4.4: the link (row) with the largest writhe against the ring is the chain segment
  // that crosses the ring's disc.
  Eigen::Matrix3Xd P;
  ChainPoints(s->robot, kin, s->report_chain, &P);
  const Eigen::Matrix3Xd& ring = s->report_object_chain;
  const Eigen::Vector3d center = ring.rowwise().mean();
  const Eigen::Vector3d normal =
      (ring.col(1) - ring.col(0)).cross(ring.col(2) - ring.col(1)).normalized();
  int crossing = -1;
  for (int i = 0; i + 1 < P.cols(); ++i) {
    const double a = (P.col(i) - center).dot(normal), b = (P.col(i + 1) - center).dot(normal);
    if (a * b <= 0.0) crossing = i;
  }
  ASSERT_GE(crossing, 0);
  Eigen::Index row = 0;
  W.rowwise().sum().cwiseAbs().maxCoeff(&row);
  EXPECT_EQ(row, crossing) << "W =\n" << W;
}

TEST(RrtBaselines, PathsAreCollisionFreeAndSeedsReproduce) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  for (Planner planner : {Planner::kRrt, Planner::kBiRrt}) {
    const PlanResult a = RunPlanner(*s, planner, 3);
    const PlanResult b = RunPlanner(*s, planner, 3);
    SCOPED_TRACE(PlannerName(planner));
    ASSERT_TRUE(a.report.success);
    EXPECT_TRUE(a.report.path_collision_free);
    EXPECT_TRUE(a.trajectory.q.col(0).isApprox(s->problem.q0));
    EXPECT_TRUE(a.trajectory.q.col(a.trajectory.num_points() - 1).isApprox(s->goal_q));
    // Independent re-check of the path at the edge resolution.
    CollisionData coll(s->robot, s->env, s->collision);
    KinematicsData kin(s->robot);
    const ValidityFn free = [&](const Eigen::VectorXd& q) {
      ForwardKinematics(s->robot, q, &kin);
      return !InCollision(s->robot, kin, &coll);
    };
    EXPECT_TRUE(PathIsValid(a.trajectory, s->check_resolution, free));
    // Same seed, same report (except the wall-clock time).
    EXPECT_EQ(a.report.collision_checks, b.report.collision_checks);
    EXPECT_EQ(a.report.iterations, b.report.iterations);
    EXPECT_EQ(a.trajectory.q, b.trajectory.q);
    EXPECT_EQ(a.report.final_writhe_total, b.report.final_writhe_total);
  }
  const PlanResult a = RunPlanner(*s, Planner::kAico, 0);
  const PlanResult b = RunPlanner(*s, Planner::kAico, 0);
  EXPECT_EQ(a.report.collision_checks, b.report.collision_checks);
  EXPECT_EQ(a.report.cost, b.report.cost);
  EXPECT_EQ(a.trajectory.q, b.trajectory.q);
}

}  // namespace
}  // namespace planning
