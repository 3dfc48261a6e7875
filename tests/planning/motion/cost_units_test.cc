// The common cost units of every planner (collision.h QueryCounts, PlanReport::counts), the
// budgets (planner.h Budget), aico-goal, the survival verdicts and the ablation list of the unwrap
// benchmark (docs/results/unwrap.md).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/features/task.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/scenario_spec.h"
#include "planning/motion/unwrap_benchmark.h"
#include "planning/robot/robot_io.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";

// A sphere (r 0.1) on a prismatic x joint against a sphere r 0.1 at (1, 0, 0).
const char* kSlider = R"(<robot name="slider">
  <link name="base"/>
  <joint name="x" type="prismatic"><parent link="base"/><child link="ball"/>
    <axis xyz="1 0 0"/><limit lower="-2" upper="2" velocity="1" effort="1"/></joint>
  <link name="ball"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
</robot>)";

TEST(CostUnits, BooleanAndDistancePairTestsAreCountedApart) {
  const Robot robot = ParseRobot(kSlider, "slider", "");
  Geometry g;
  g.kind = Geometry::Kind::kSphere;
  g.size = Eigen::Vector3d(0.1, 0, 0);
  Environment env;
  AddObject(MakePrimitiveObject("obstacle", g),
            Eigen::Isometry3d(Eigen::Translation3d(1.0, 0.0, 0.0)), "obstacle", &env);
  KinematicsData kin(robot);
  CollisionData coll(robot, env);
  Eigen::VectorXd q(1);
  q << 0.85;  // 5 cm penetration: the one pair reaches the narrow phase
  ForwardKinematics(robot, q, &kin);
  EXPECT_TRUE(InCollision(robot, kin, &coll));
  // One boolean query: one yes/no pair test, no distance.
  EXPECT_EQ(Counts(coll), (QueryCounts{1, 1, 0}));
  EXPECT_EQ(coll.narrow_phase_calls, 1);
  const QueryCounts before = Counts(coll);
  MinDistance(robot, kin, &coll);
  const QueryCounts d = Counts(coll) - before;
  EXPECT_EQ(d.state_queries, 1);
  EXPECT_EQ(d.bool_pair_tests, 0);
  EXPECT_GE(d.distance_pair_tests, 1);
  // The split is exhaustive: every narrow-phase call is one of the two kinds.
  EXPECT_EQ(coll.bool_pair_tests + coll.distance_pair_tests, coll.narrow_phase_calls);
}

TEST(CostUnits, OneStateQueryPerConfigurationThatQueriesTheWorld) {
  ScenarioOverrides o;
  o.start_wrap_deg = 90.0;
  const auto s = LoadScenario(kAssets + "scenarios/unwrap.json", o);
  const MotionProblem& p = s->initial.problem;
  EXPECT_EQ(WritheTaskNames(p), std::vector<std::string>{"writhe"});  // a writhe_total feature
  TaskWorkspace ws(p);
  // All tasks at once: collision, line clearance and winding are evaluated, one state query.
  EvaluateTasks(p, -1, p.q0, true, &ws);
  QueryCounts c = TaskQueryCounts(p, ws);
  EXPECT_EQ(c.state_queries, 1);
  EXPECT_EQ(ws.state_queries, 1);
  // Line clearance and winding: one distance pair test per arm segment each, plus the collision
  // feature's proximity pairs.
  const int segments = ChainSize(s->robot, FindChain(s->robot, "arm")) - 1;
  EXPECT_GT(segments, 0);
  EXPECT_GE(c.distance_pair_tests, 2 * segments);
  EXPECT_EQ(c.bool_pair_tests, 0);  // features make no boolean tests
  // A task that does not query the world (joint limits) costs no state query; the winding guard
  // alone costs one.
  int limits = -1, guard = -1;
  for (size_t i = 0; i < p.tasks.size(); ++i) {
    if (p.tasks[i].name == "limits") limits = static_cast<int>(i);
    if (p.tasks[i].name == "winding_guard") guard = static_cast<int>(i);
  }
  ASSERT_GE(limits, 0);
  ASSERT_GE(guard, 0);
  EvaluateTask(p, limits, p.q0, false, &ws);
  EXPECT_EQ(TaskQueryCounts(p, ws).state_queries, 1);
  EvaluateTask(p, guard, p.q0, false, &ws);
  c = TaskQueryCounts(p, ws);
  EXPECT_EQ(c.state_queries, 2);
}

TEST(CostUnits, EveryPlannerCountsTheSameWayAndRepeats) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  for (Planner planner : {Planner::kAico, Planner::kRrt, Planner::kBiRrt, Planner::kAicoGoal}) {
    SCOPED_TRACE(PlannerName(planner));
    const PlanReport a = RunPlanner(*s, planner, 0).report;
    const PlanReport b = RunPlanner(*s, planner, 0).report;
    EXPECT_GT(a.counts.state_queries, 0);
    EXPECT_GT(a.counts.pair_tests(), 0);
    EXPECT_EQ(a.counts, b.counts);  // deterministic
    EXPECT_GE(a.cpu_time_s, 0.0);
    // reach_through_ring has no line-clearance or winding term: the only world queries are the
    // collision feature's and the validity checks, so the new units agree with the old counters.
    EXPECT_EQ(a.counts.state_queries, a.collision_checks);
    EXPECT_EQ(a.counts.pair_tests(), a.narrow_phase_calls);
    if (IsAico(planner)) {
      EXPECT_GT(a.counts.distance_pair_tests, 0);  // the collision feature
      EXPECT_GT(a.counts.bool_pair_tests, 0);      // the validation at check_resolution
    } else {
      EXPECT_EQ(a.counts.distance_pair_tests, 0);  // validity checks are boolean
    }
  }
}

TEST(Budget, ParsesBothUnitsAndNamesTheFlag) {
  Budget b = ParseBudget("queries=5000", "--budget");
  EXPECT_EQ(b.unit, Budget::Unit::kQueries);
  EXPECT_EQ(b.value, 5000.0);
  EXPECT_EQ(BudgetText(b), "queries=5000");
  b = ParseBudget("700", "--budget");
  EXPECT_EQ(b.unit, Budget::Unit::kQueries);
  EXPECT_EQ(b.value, 700.0);
  b = ParseBudget("time=2.5", "--budget");
  EXPECT_EQ(b.unit, Budget::Unit::kCpuTime);
  EXPECT_EQ(b.value, 2.5);
  EXPECT_EQ(BudgetText(b), "time=2.5");
  b = ParseBudget("pairs=250", "--budget");
  EXPECT_EQ(b.unit, Budget::Unit::kPairTests);
  EXPECT_EQ(BudgetText(b), "pairs=250");
  EXPECT_EQ(BudgetText(Budget{}), "");
  for (const char* bad : {"", "-5", "queries=0", "queries=1.5", "time=0", "time=nan", "wall=3",
                          "queries=", "time=1s", "pairs=0.5", "queries=0x10", "queries=1e3",
                          "queries=+5", "pairs=10000000000000", "queries= 5"}) {
    SCOPED_TRACE(bad);
    try {
      ParseBudget(bad, "--budget");
      FAIL();
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--budget: ", 0), 0u) << e.what();
    }
  }
}

TEST(Budget, ABudgetOnlyTruncatesARun) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  for (Planner planner : {Planner::kRrt, Planner::kBiRrt, Planner::kAico}) {
    SCOPED_TRACE(PlannerName(planner));
    const PlanResult free = RunPlanner(*s, planner, 0);
    ASSERT_TRUE(free.report.success);
    EXPECT_TRUE(SolvedWithin(free.report, Budget{}));
    const double spent = static_cast<double>(free.report.counts.state_queries);
    EXPECT_TRUE(SolvedWithin(free.report, Budget{Budget::Unit::kQueries, spent}));
    EXPECT_FALSE(SolvedWithin(free.report, Budget{Budget::Unit::kQueries, spent - 1}));
    // A budget far below what the run needs: budget exhausted, not another failure.
    PlanRequest request;
    request.planner = planner;
    request.budget = Budget{Budget::Unit::kQueries, 3};
    const PlanReport cut = RunPlanner(*s, request).report;
    EXPECT_FALSE(cut.success);
    EXPECT_EQ(cut.failure_reason, FailureReason::kBudgetExhausted);
    if (!IsAico(planner)) {
      EXPECT_LE(cut.counts.state_queries, 3);
      // The budget the run needed: the same run, the same counts and path.
      request.budget = Budget{Budget::Unit::kQueries, spent};
      const PlanResult exact = RunPlanner(*s, request);
      EXPECT_TRUE(exact.report.success);
      EXPECT_EQ(exact.report.counts, free.report.counts);
      EXPECT_EQ(exact.trajectory.q, free.trajectory.q);
    }
    // A run that succeeds within a budget has spent no more than it (AICO checks the budget after
    // each sweep: a success that sweep reaches past the budget is a budget failure).
    for (const double b : {spent / 2, spent - 1, spent}) {
      request.budget = Budget{Budget::Unit::kQueries, b};
      const PlanReport r = RunPlanner(*s, request).report;
      EXPECT_TRUE(r.success ? SolvedWithin(r, request.budget)
                            : r.failure_reason == FailureReason::kBudgetExhausted)
          << b << ": " << r.counts.state_queries << " queries, "
          << FailureReasonName(r.failure_reason);
      if (b < spent) {
        EXPECT_FALSE(r.success) << b;
      }
    }
    // The same in pair tests: a tiny budget stops the run; SolvedWithin reads the run's tests.
    const double pairs = static_cast<double>(free.report.counts.pair_tests());
    EXPECT_TRUE(SolvedWithin(free.report, Budget{Budget::Unit::kPairTests, pairs}));
    EXPECT_FALSE(SolvedWithin(free.report, Budget{Budget::Unit::kPairTests, pairs - 1}));
    request.budget = Budget{Budget::Unit::kPairTests, 3};
    const PlanReport few = RunPlanner(*s, request).report;
    EXPECT_FALSE(few.success);
    EXPECT_EQ(few.failure_reason, FailureReason::kBudgetExhausted);
  }
}

TEST(AicoGoal, SwitchesOffTheWritheTermsOnly) {
  const auto s = LoadScenario(kAssets + "scenarios/reach_through_ring.json");
  EXPECT_EQ(ParsePlanner("aico-goal"), Planner::kAicoGoal);
  EXPECT_TRUE(IsAico(Planner::kAicoGoal));
  EXPECT_EQ(WritheTaskNames(s->initial.problem), std::vector<std::string>{"writhe"});
  MotionProblem p = AttemptProblem(*s, 0);
  DisableTasks({"writhe"}, &p);
  for (const Task& t : p.tasks) {
    if (t.name == "writhe") {
      EXPECT_EQ(t.precision.maxCoeff(), 0.0);
    } else {
      EXPECT_GT(t.precision.maxCoeff(), 0.0) << t.name;
    }
  }
  EXPECT_THROW(DisableTasks({"nope"}, &p), std::invalid_argument);
  const PlanReport goal = RunPlanner(*s, Planner::kAicoGoal, 0).report;
  const PlanReport full = RunPlanner(*s, Planner::kAico, 0).report;
  EXPECT_EQ(goal.planner, "aico-goal");
  // Without its writhe term the solve is a different one (the writhe target pulls the hand
  // through the ring), judged by the same criteria.
  EXPECT_NE(goal.counts, full.counts);
  PlanRequest r;
  r.planner = Planner::kAico;
  r.disabled_tasks = {"nope"};
  EXPECT_THROW(RunPlanner(*s, r), std::invalid_argument);
}

TEST(UnwrapAblations, OneVariantPerTaskTermOfTheScenario) {
  const ScenarioSpec spec = ParseScenarioSpec(kAssets + "scenarios/unwrap.json");
  const std::vector<UnwrapAblation> a = UnwrapAblations(spec);
  std::vector<std::string> names;
  for (const UnwrapAblation& x : a) names.push_back(x.name);
  EXPECT_EQ(names, (std::vector<std::string>{"full", "no-writhe", "no-reach", "no-off-pole",
                                             "no-winding-guard", "no-rollout"}));
  EXPECT_TRUE(a[0].disabled_tasks.empty());
  EXPECT_EQ(a[1].disabled_tasks, std::vector<std::string>{"writhe"});
  EXPECT_EQ(a[2].disabled_tasks, std::vector<std::string>{"reach"});
  EXPECT_EQ(a[3].disabled_tasks, std::vector<std::string>{"off_pole_line"});
  EXPECT_EQ(a[4].disabled_tasks, std::vector<std::string>{"winding_guard"});
  EXPECT_TRUE(a[5].no_rollout);
  EXPECT_TRUE(a[5].disabled_tasks.empty());
}

// A run of the survival tests: planner, angle, success, state queries, CPU seconds, status.
UnwrapRun MakeRun(Planner planner, double angle, bool success, long queries, double cpu,
                  SolveStatus status) {
  UnwrapRun r;
  r.planner = planner;
  r.angle_deg = angle;
  r.report.success = success;
  r.report.counts.state_queries = queries;
  r.report.cpu_time_s = cpu;
  r.report.status = status;
  r.report.failure_reason = success                             ? FailureReason::kNone
                            : status == SolveStatus::kConverged ? FailureReason::kWritheNotReached
                                                                : FailureReason::kBudgetExhausted;
  return r;
}

TEST(UnwrapSurvival, FractionSolvedWithinEachBudgetAndWhyTheOthersFailed) {
  UnwrapBenchmarkResult result;
  result.angles_deg = {540.0};
  result.planners = {Planner::kAico, Planner::kBiRrt};
  result.seeds = 4;
  result.runs = {MakeRun(Planner::kAico, 540, true, 500, 0.5, SolveStatus::kSolved),
                 MakeRun(Planner::kAico, 540, true, 800, 0.8, SolveStatus::kSolved),
                 MakeRun(Planner::kAico, 540, false, 900, 0.9, SolveStatus::kConverged),
                 MakeRun(Planner::kAico, 540, true, 2000, 2.0, SolveStatus::kSolved),
                 MakeRun(Planner::kBiRrt, 540, true, 50000, 1.0, SolveStatus::kConverged),
                 MakeRun(Planner::kBiRrt, 540, false, 100000, 3.0, SolveStatus::kBudgetExhausted),
                 MakeRun(Planner::kBiRrt, 540, true, 90000, 2.5, SolveStatus::kConverged),
                 MakeRun(Planner::kBiRrt, 540, true, 10, 0.1, SolveStatus::kConverged)};
  const std::vector<double> budgets = LogBudgets(100, 100000, 4);  // 100, 1e3, 1e4, 1e5
  ASSERT_EQ(budgets.size(), 4u);
  EXPECT_DOUBLE_EQ(budgets[1], 1000.0);
  const auto pts = UnwrapSurvival(result, Budget::Unit::kQueries, budgets);
  ASSERT_EQ(pts.size(), 8u);
  const std::vector<int> aico = {0, 2, 3, 3}, birrt = {1, 1, 1, 3};
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(pts[k].solved, aico[k]) << k;
    EXPECT_EQ(pts[4 + k].solved, birrt[k]) << k;
    EXPECT_EQ(pts[k].runs, 4);
  }
  EXPECT_EQ(pts[0].failed_other, 1);  // AICO converged to a failure: no budget solves it
  EXPECT_EQ(pts[0].failed_budget, 0);
  EXPECT_EQ(pts[4].failed_budget, 1);  // BiRRT stopped at its budget
  EXPECT_EQ(pts[4].failed_other, 0);
  const auto cpu = UnwrapSurvival(result, Budget::Unit::kCpuTime, {1.0});
  EXPECT_EQ(cpu[0].solved, 2);
  EXPECT_EQ(cpu[1].solved, 2);
  const std::string csv = UnwrapSurvivalCsv(pts);
  EXPECT_EQ(csv.rfind("unit,budget,planner,angle_deg,runs,solved,fraction,failed_budget,"
                      "failed_other\n",
                      0),
            0u);
  EXPECT_NE(csv.find("state_queries,1000,aico,540,4,2,0.5,0,1\n"), std::string::npos) << csv;
  EXPECT_THROW(LogBudgets(0, 10, 3), std::invalid_argument);
}

}  // namespace
}  // namespace planning
