// OMPL peer check (built only with OMPL): the edge rule translated into OMPL's resolution fraction
// checks the same states as rrt.h; ompl-rrtconnect on reach_through_ring finds a path that the
// project's own checker accepts at the check resolution; the budget ends a run as failed; same
// seed, same report.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "planning/motion/internal/ompl_planners.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/success.h"
#include "planning/robot/kinematics.h"
#include "scenario_test_util.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";

TEST(OmplPeers, ParsePlannerAcceptsTheOmplNames) {
  ASSERT_TRUE(OmplAvailable());
  EXPECT_EQ(ParsePlanner("ompl-rrt"), Planner::kOmplRrt);
  EXPECT_EQ(ParsePlanner("ompl-rrtconnect"), Planner::kOmplRrtConnect);
  EXPECT_STREQ(PlannerName(Planner::kOmplRrtConnect), "ompl-rrtconnect");
}

// Free 2-D box, goal 0.95 from the start (within range), goal bias 1: the first extension is the
// whole edge. Checked: the start, then the end state, then the ⌈0.95 / 0.1⌉ − 1 = 9 interior
// states at i/10 of the edge — the states of the rrt.h rule, so the resolution reached OMPL
// unchanged. (OMPL visits the interior states in bisection order, rrt.h in sequence: the same set
// on a valid edge; on an invalid one the two may stop after different numbers of checks.)
TEST(OmplPeers, EdgeResolutionMatchesTheProjectRule) {
  RrtProblem p;
  p.lower = Eigen::Vector2d(-1.0, -1.0);
  p.upper = Eigen::Vector2d(1.0, 1.0);
  p.start = Eigen::Vector2d(-0.5, 0.0);
  p.goal = Eigen::Vector2d(0.45, 0.0);
  RrtOptions o;
  o.range = 1.0;
  o.resolution = 0.1;
  o.goal_bias = 1.0;
  std::vector<Eigen::VectorXd> seen;
  const ValidityFn valid = [&](const Eigen::VectorXd& q) {
    seen.push_back(q);
    return true;
  };
  const RrtResult r = internal::PlanOmpl(internal::OmplPlanner::kRrt, p, o, valid, 0);
  ASSERT_EQ(r.status, SolveStatus::kConverged);
  ASSERT_EQ(r.checks, 11);
  ASSERT_EQ(seen.size(), 11u);
  EXPECT_TRUE(seen[0].isApprox(p.start));
  EXPECT_TRUE(seen[1].isApprox(p.goal));
  std::sort(seen.begin() + 2, seen.end(),
            [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return a[0] < b[0]; });
  for (int i = 1; i < 10; ++i) {
    const Eigen::VectorXd expected = p.start + (i / 10.0) * (p.goal - p.start);
    EXPECT_LT((seen[1 + i] - expected).norm(), 1e-12) << "interior state " << i;
  }
  ASSERT_EQ(r.path.num_points(), 2);
  EXPECT_TRUE(r.path.q.col(1).isApprox(p.goal));
}

TEST(OmplPeers, BudgetEndsTheRunAsFailed) {
  RrtProblem p;
  p.lower = Eigen::Vector2d(-1.0, -1.0);
  p.upper = Eigen::Vector2d(1.0, 1.0);
  p.start = Eigen::Vector2d(-0.9, 0.0);
  p.goal = Eigen::Vector2d(0.9, 0.0);
  RrtOptions o;
  o.max_checks = 200;
  long calls = 0;
  // A wall at x = 0 with no gap: no path exists.
  const ValidityFn valid = [&](const Eigen::VectorXd& q) {
    ++calls;
    return std::abs(q[0]) > 0.05;
  };
  for (auto planner : {internal::OmplPlanner::kRrt, internal::OmplPlanner::kRrtConnect}) {
    calls = 0;
    const RrtResult r = internal::PlanOmpl(planner, p, o, valid, 1);
    EXPECT_EQ(r.status, SolveStatus::kBudgetExhausted);
    EXPECT_EQ(r.checks, 200);
    EXPECT_EQ(calls, 200);
    EXPECT_EQ(r.path.num_points(), 0);
  }
}

TEST(OmplPeers, GoalRegionTheSamplerCannotHitEndsAtTheDrawCap) {
  // The sampler never yields a goal state: RRTConnect waits for its first goal tree and every
  // candidate outside G costs no check, so only the draw cap (max_checks draws) ends the run.
  GoalRegionProblem p;
  p.lower = Eigen::Vector2d(-1.0, -1.0);
  p.upper = Eigen::Vector2d(1.0, 1.0);
  p.start = Eigen::Vector2d(-0.9, 0.0);
  long draws = 0;
  p.goal.contains = [](const Eigen::VectorXd&) { return false; };
  p.goal.sample = [&draws](std::mt19937*, Eigen::VectorXd* q) {
    ++draws;
    q->setZero();
    return false;
  };
  GoalRegionOptions o;
  o.rrt.max_checks = 500;
  const ValidityFn valid = [](const Eigen::VectorXd&) { return true; };
  for (auto planner : {internal::OmplPlanner::kRrt, internal::OmplPlanner::kRrtConnect}) {
    draws = 0;
    const RrtResult r = internal::PlanOmplRegion(planner, p, o, valid, 1);
    EXPECT_EQ(r.status, SolveStatus::kBudgetExhausted);
    EXPECT_EQ(r.path.num_points(), 0);
    EXPECT_EQ(r.goal.draws, draws);
    EXPECT_LE(r.checks, o.rrt.max_checks);
    // RRTConnect stops within one sampleGoal call (kOmplGoalDraws draws) of the cap.
    EXPECT_LE(draws, o.rrt.max_checks + internal::kOmplGoalDraws);
    if (planner == internal::OmplPlanner::kRrtConnect) {
      EXPECT_GE(draws, o.rrt.max_checks);
    }
  }
}

TEST(OmplPeers, RrtConnectOnReachThroughRingIsCollisionFreeAndSeedsReproduce) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  const PlanResult a = RunPlanner(*s, Planner::kOmplRrtConnect, 3);
  const PlanResult b = RunPlanner(*s, Planner::kOmplRrtConnect, 3);
  EXPECT_EQ(a.report.planner, "ompl-rrtconnect");
  ASSERT_EQ(a.report.status, SolveStatus::kConverged);
  EXPECT_TRUE(a.report.success);
  EXPECT_TRUE(a.report.path_collision_free);
  EXPECT_GT(a.report.collision_checks, 0);
  EXPECT_LE(a.report.collision_checks, s->rrt.max_checks);
  EXPECT_GT(a.report.iterations, 0);
  EXPECT_NEAR(a.report.cost, a.report.path_length, 1e-12);
  EXPECT_TRUE(a.trajectory.q.col(0).isApprox(s->initial.problem.q0));
  EXPECT_TRUE(a.trajectory.q.col(a.trajectory.num_points() - 1).isApprox(s->goal_q));
  // Independent re-check of the path with the project's checker at the check resolution.
  EXPECT_TRUE(PathCollisionFree(*s, a.trajectory));
  // Same seed, same report (except the wall-clock time), even after other OMPL runs.
  EXPECT_EQ(a.report.collision_checks, b.report.collision_checks);
  EXPECT_EQ(a.report.iterations, b.report.iterations);
  EXPECT_EQ(a.trajectory.q, b.trajectory.q);
}

TEST(OmplPeers, BudgetInAScenarioRunIsAFailedReport) {
  auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  s->rrt.max_checks = 30;
  const PlanResult r = RunPlanner(*s, Planner::kOmplRrt, 0);
  EXPECT_FALSE(r.report.success);
  EXPECT_EQ(r.report.status, SolveStatus::kBudgetExhausted);
  EXPECT_EQ(r.report.collision_checks, 30);
  EXPECT_EQ(r.trajectory.num_points(), 0);
}

// The OMPL peers of the goal-region trees: registered, kept out of the default sweep, and
// ompl-rrtconnect-region unwraps the shipped arm from 360° into the region the criterion judges,
// deterministically per seed.
TEST(OmplPeers, GoalRegionPeersAreRegisteredButNotDefault) {
  EXPECT_EQ(ParsePlanner("ompl-rrt-region"), Planner::kOmplRrtRegion);
  EXPECT_EQ(ParsePlanner("ompl-rrtconnect-region"), Planner::kOmplRrtConnectRegion);
  const std::vector<Planner> all = AvailablePlanners(), def = DefaultPlanners();
  EXPECT_NE(std::find(all.begin(), all.end(), Planner::kOmplRrtConnectRegion), all.end());
  EXPECT_EQ(std::find(def.begin(), def.end(), Planner::kOmplRrtConnectRegion), def.end());
  EXPECT_EQ(std::find(def.begin(), def.end(), Planner::kOmplRrtRegion), def.end());
  EXPECT_EQ(def.size() + 2, all.size());
}

TEST(OmplPeers, RrtConnectRegionUnwrapsFrom360Degrees) {
  ScenarioOverrides o;
  o.start_wrap_deg = 360.0;
  const auto s = LoadScenario(kAssets + "scenarios/unwrap.json", o);
  const PlanResult a = RunPlanner(*s, Planner::kOmplRrtConnectRegion, 0);
  const PlanReport& r = a.report;
  EXPECT_EQ(r.planner, "ompl-rrtconnect-region");
  ASSERT_TRUE(r.success) << FailureReasonName(r.failure_reason);
  const Trajectory& path = a.trajectory;
  EXPECT_TRUE(CheckEndState(*s, path.q.col(path.num_points() - 1), true).ok());
  EXPECT_TRUE(JudgePlan(*s, path).ok());
  EXPECT_TRUE(PathCollisionFree(*s, path));
  EXPECT_GT(r.goal_samples, 0);
  EXPECT_GE(r.goal_sampler_draws, r.goal_samples);
  EXPECT_GT(r.goal_sampler_counts.state_queries, 0);
  EXPECT_LE(r.collision_checks, s->rrt.max_checks);
  const PlanReport again = RunPlanner(*s, Planner::kOmplRrtConnectRegion, 0).report;
  EXPECT_EQ(again.counts, r.counts);
  EXPECT_EQ(again.goal_samples, r.goal_samples);
}

}  // namespace
}  // namespace planning
