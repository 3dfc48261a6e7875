// The AICO retry from the unwinding path ("aico": {"retry": {"init": "unwinding"}}): the init, the
// attempt it runs, what it is charged, who does not get it, and its keys.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "planning/motion/internal/start_coil.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/scenario_spec.h"
#include "planning/motion/unwrap_benchmark.h"
#include "planning/motion/unwrap_geometry.h"
#include "scenario_test_util.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";
const std::string kChord = kAssets + "scenarios/unwrap_chord.json";

// unwrap_chord.json on tuning_06 (30-link arm, moved pole) at 540°: the rollout-init attempt ends
// with the writhe target missed; the retry from the unwinding path solves it.
std::unique_ptr<Scenario> Tuning06() {
  const UnwrapGeometry g =
      ReadUnwrapGeometry(kAssets + "scenarios/unwrap_geometries/tuning/tuning_06_arm30.json");
  ScenarioSpec spec = ParseScenarioSpec(kChord);
  ApplyUnwrapGeometry(g, &spec);
  return SetUpScenario(spec, 540.0);
}

TEST(UnwindingRetry, TheInitIsTheContinuationOfTheStartToWritheZero) {
  const auto s = Tuning06();
  QueryCounts counts;
  const Trajectory init = internal::UnwindingInit(*s, s->initial, s->initial.problem.q0, &counts);
  ASSERT_EQ(init.num_points(), s->spec.problem.num_steps + 1);
  ASSERT_EQ(init.num_dofs(), s->initial.problem.q0.size());
  EXPECT_DOUBLE_EQ(init.dt, s->spec.problem.duration / s->spec.problem.num_steps);
  EXPECT_TRUE(init.q.col(0).isApprox(s->initial.problem.q0, 1e-12));
  EXPECT_GT(std::abs(ReportWritheTotal(*s, init.q.col(0))), 1.4);  // 540°
  EXPECT_LT(std::abs(ReportWritheTotal(*s, init.q.col(init.num_points() - 1))), 0.05);
  // The continuation's path resampled by joint-space arc length.
  std::vector<Eigen::VectorXd> path;
  internal::WritheContinuation(*s, s->initial.problem.q0, 0.0, s->spec.start.step,
                               s->spec.start.margin, &path);
  EXPECT_GT(path.size(), 20u);
  EXPECT_TRUE(init.q.isApprox(internal::ResampleByArcLength(path, init.num_points()), 1e-12));
  EXPECT_GT(counts.state_queries, 0);
  EXPECT_GT(counts.pair_tests(), 0);
}

// The continuation runs in the world planned in: with the pole moved, the init unwinds about the
// pole where it is (its writhe with the moved pole ends near 0), not where the file put it.
TEST(UnwindingRetry, TheInitFollowsAMovedPole) {
  const auto s = Tuning06();
  const auto moved = MakeScenarioState(*s);
  MoveObject(*s, moved.get(), "pole",
             ObjectPosition(*s, *moved, "pole") + Eigen::Vector3d(0.0, 0.0, 0.05));
  QueryCounts counts;
  const Eigen::VectorXd& q0 = s->initial.problem.q0;
  const Trajectory there = internal::UnwindingInit(*s, *moved, q0, &counts);
  const Trajectory here = internal::UnwindingInit(*s, s->initial, q0, &counts);
  EXPECT_FALSE(there.q.isApprox(here.q, 1e-6));
  EXPECT_LT(std::abs(ReportWritheTotal(*s, *moved, there.q.col(there.num_points() - 1))), 0.05);
}

// An L-shaped path of lengths 1 + 1 at 5 equally spaced arc lengths: the corner is kept.
TEST(UnwindingRetry, ResamplingIsByArcLength) {
  const std::vector<Eigen::VectorXd> path = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0),
                                             Eigen::Vector2d(1, 1)};
  Eigen::MatrixXd expected(2, 5);
  expected << 0, 0.5, 1, 1, 1,  //
      0, 0, 0, 0.5, 1;
  EXPECT_TRUE(internal::ResampleByArcLength(path, 5).isApprox(expected, 1e-15));
  // One configuration: repeated.
  const Eigen::MatrixXd one = internal::ResampleByArcLength({Eigen::Vector2d(2, 3)}, 3);
  EXPECT_TRUE((one.colwise() - Eigen::Vector2d(2, 3)).isZero());
}

TEST(UnwindingRetry, ARolloutFailureIsSolvedByTheRetryWhichIsCharged) {
  const auto s = Tuning06();
  ASSERT_EQ(s->aico_attempts.size(), 2u);
  EXPECT_TRUE(s->aico_attempts[1].init_unwinding);
  PlanRequest request;
  request.aico_retry = false;
  const PlanReport first = RunPlanner(*s, request).report;
  EXPECT_FALSE(first.success);
  EXPECT_EQ(first.attempts, 1);
  request.aico_retry = true;
  const PlanReport both = RunPlanner(*s, request).report;
  EXPECT_TRUE(both.success) << FailureReasonName(both.failure_reason);
  EXPECT_EQ(both.attempts, 2);
  QueryCounts init;
  internal::UnwindingInit(*s, s->initial, s->initial.problem.q0, &init);
  // Attempt 0 as before, the continuation, and attempt 1's own queries.
  EXPECT_GT(both.counts.state_queries, first.counts.state_queries + init.state_queries);
  EXPECT_GT(both.counts.pair_tests(), first.counts.pair_tests() + init.pair_tests());
  // A budget the continuation reaches: the retry does not start, and the run has spent exactly
  // attempt 0 and the continuation.
  request.budget = {Budget::Unit::kQueries,
                    static_cast<double>(first.counts.state_queries + init.state_queries)};
  const PlanReport cut = RunPlanner(*s, request).report;
  EXPECT_FALSE(cut.success);
  EXPECT_EQ(cut.status, SolveStatus::kBudgetExhausted);
  EXPECT_EQ(cut.failure_reason, FailureReason::kBudgetExhausted);
  EXPECT_EQ(cut.attempts, 1);  // the retry did not start
  EXPECT_EQ(cut.counts, first.counts + init);
}

// The unwinding path is writhe-driven: aico-goal and the no-writhe ablation (no writhe term) do
// not get it. Both fail here, and spend what they spend without a retry.
TEST(UnwindingRetry, NoUnwindingAttemptWithoutTheWritheTerm) {
  const auto s = Tuning06();
  for (const bool goal : {true, false}) {
    SCOPED_TRACE(goal ? "aico-goal" : "no-writhe");
    PlanRequest request;
    request.planner = goal ? Planner::kAicoGoal : Planner::kAico;
    if (!goal) request.disabled_tasks = {"writhe"};
    const PlanReport r = RunPlanner(*s, request).report;
    EXPECT_FALSE(r.success);
    EXPECT_EQ(r.attempts, 1);
    request.aico_retry = false;
    EXPECT_EQ(RunPlanner(*s, request).report.counts, r.counts);
  }
}

TEST(UnwindingRetry, TheAblationsHaveANoRetryVariant) {
  const std::vector<UnwrapAblation> a = UnwrapAblations(ParseScenarioSpec(kChord));
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a.back().name, "no-retry");
  EXPECT_TRUE(a.back().no_retry);
  EXPECT_TRUE(a.back().disabled_tasks.empty());
  for (size_t i = 0; i + 1 < a.size(); ++i) EXPECT_FALSE(a[i].no_retry) << a[i].name;
}

std::string WriteTemp(const std::string& name, const std::string& text) {
  return WriteTestFile("unwinding_retry_test_tmp", name, text);
}

// A small scenario (LWR4 + SDH, zero start, T = 5) with `writhe_report` and an aico section.
std::string Mini(const std::string& writhe_report, const std::string& aico) {
  return R"({"robot": ")" + kAssets + R"(robots/lwr4_sdh.urdf",
    "objects": [{"name": "pole", "urdf": ")" +
         kAssets + R"(objects/pole.urdf", "xyz": [0.6, 0.1, 0.5]}],)" + writhe_report + R"(
    "start": {"q": "zero"}, "problem": {"T": 5},
    "tasks": [{"name": "reach", "feature": {"type": "position", "link": "sdh_grasp_link"},
               "target": {"value": [0.5, 0, 0.5]}, "precision": 1}],
    "aico": )" +
         aico + "}";
}

void ExpectError(const std::string& name, const std::string& text, const std::string& fragment) {
  try {
    SetUpScenario(ParseScenarioSpec(WriteTemp(name, text)));
    ADD_FAILURE() << "expected an error naming " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(UnwindingRetry, KeysAreChecked) {
  const std::string report =
      R"( "writhe_report": {"chain": "arm", "object": "pole", "object_chain": "axis"},)";
  ExpectError("bad_init.json", Mini(report, R"({"retry": {"init": "rollout"}})"),
              "aico.retry.init: \"rollout\" is not \"unwinding\"");
  ExpectError("no_report.json", Mini("", R"({"retry": {"init": "unwinding"}})"),
              "aico.retry.init: the unwinding init continues the writhe_report's writhe");
  const auto s = SetUpScenario(
      ParseScenarioSpec(WriteTemp("ok.json", Mini(report, R"({"retry": {"init": "unwinding"}})"))));
  ASSERT_EQ(s->aico_attempts.size(), 2u);
  EXPECT_FALSE(s->aico_attempts[0].init_unwinding);
  EXPECT_TRUE(s->aico_attempts[1].init_unwinding);
}

}  // namespace
}  // namespace planning
