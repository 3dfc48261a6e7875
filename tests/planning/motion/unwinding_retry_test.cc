// The AICO retries from the unwinding paths (unwrap_chord.json's "aico": {"retry": [{"init":
// "unwinding"}, {"init": "unwinding_then_reach"}, {"init": "unwinding", "precision_scale": ...},
// {"init": "winding_then_reach"}]}): the inits, the attempts they run, what they are charged, who
// does not get them, and their keys.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "planning/motion/internal/start_coil.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/scenario_spec.h"
#include "planning/motion/success.h"
#include "planning/motion/unwrap_benchmark.h"
#include "planning/motion/unwrap_geometry.h"
#include "scenario_test_util.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";
const std::string kChord = kAssets + "scenarios/unwrap_chord.json";

// unwrap_chord.json on the shipped tuning geometry `name` at `wrap_deg`, with its first `attempts`
// AICO attempts (unwrap_chord.json has 5).
std::unique_ptr<Scenario> ShippedTuning(const std::string& name, double wrap_deg, int attempts) {
  const UnwrapGeometry g =
      ReadUnwrapGeometry(kAssets + "scenarios/unwrap_geometries/tuning/" + name + ".json");
  ScenarioSpec spec = ParseScenarioSpec(kChord);
  ApplyUnwrapGeometry(g, &spec);
  spec.aico_attempts.resize(static_cast<size_t>(attempts));
  return SetUpScenario(spec, wrap_deg);
}

// unwrap_chord.json on tuning_06 (30-link arm, moved pole) at 540°: the rollout-init attempt ends
// with the writhe target missed; the retry from the unwinding path solves it.
std::unique_ptr<Scenario> Tuning06() { return ShippedTuning("tuning_06_arm30", 540.0, 5); }

TEST(UnwindingRetry, TheInitIsTheContinuationOfTheStartToWritheZero) {
  const auto s = Tuning06();
  internal::InitCounts counts;
  const Trajectory init = internal::UnwindingInit(
      *s, s->initial, s->initial.problem.q0, AicoInit::kUnwinding, s->initial.problem, &counts);
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
  EXPECT_GT(counts.units.state_queries, 0);
  EXPECT_GT(counts.units.pair_tests(), 0);
  // Its only world query is its collision task: every state query is a collision query, every
  // pair test an FCL call.
  EXPECT_EQ(counts.collision_queries, counts.units.state_queries);
  EXPECT_EQ(counts.narrow_phase_calls, counts.units.pair_tests());
}

// The continuation runs in the world planned in: with the pole moved, the init unwinds about the
// pole where it is (its writhe with the moved pole ends near 0), not where the file put it.
TEST(UnwindingRetry, TheInitFollowsAMovedPole) {
  const auto s = Tuning06();
  const auto moved = MakeScenarioState(*s);
  MoveObject(*s, moved.get(), "pole",
             ObjectPosition(*s, *moved, "pole") + Eigen::Vector3d(0.0, 0.0, 0.05));
  internal::InitCounts counts;
  const Eigen::VectorXd& q0 = s->initial.problem.q0;
  const Trajectory there =
      internal::UnwindingInit(*s, *moved, q0, AicoInit::kUnwinding, moved->problem, &counts);
  const Trajectory here = internal::UnwindingInit(*s, s->initial, q0, AicoInit::kUnwinding,
                                                  s->initial.problem, &counts);
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
  ASSERT_EQ(s->aico_attempts.size(), 5u);
  EXPECT_TRUE(s->aico_attempts[1].init == AicoInit::kUnwinding);
  EXPECT_TRUE(s->aico_attempts[2].init == AicoInit::kUnwindingThenReach);
  EXPECT_TRUE(s->aico_attempts[3].init == AicoInit::kUnwinding);
  EXPECT_TRUE(s->aico_attempts[4].init == AicoInit::kWindingThenReach);
  PlanRequest request;
  request.aico_retry = false;
  const PlanReport first = RunPlanner(*s, request).report;
  EXPECT_FALSE(first.success);
  EXPECT_EQ(first.attempts, 1);
  request.aico_retry = true;
  const PlanReport both = RunPlanner(*s, request).report;
  EXPECT_TRUE(both.success) << FailureReasonName(both.failure_reason);
  EXPECT_EQ(both.attempts, 2);  // attempt 1 solved it: attempt 2 did not run
  internal::InitCounts init;
  internal::UnwindingInit(*s, s->initial, s->initial.problem.q0, AicoInit::kUnwinding,
                          s->initial.problem, &init);
  // Attempt 0 as before, the continuation, and attempt 1's own queries.
  EXPECT_GT(both.counts.state_queries, first.counts.state_queries + init.units.state_queries);
  EXPECT_GT(both.counts.pair_tests(), first.counts.pair_tests() + init.units.pair_tests());
  // A budget the continuation reaches: the retry does not start, and the run has spent exactly
  // attempt 0 and the continuation.
  request.budget = {Budget::Unit::kQueries,
                    static_cast<double>(first.counts.state_queries + init.units.state_queries)};
  const PlanReport cut = RunPlanner(*s, request).report;
  EXPECT_FALSE(cut.success);
  EXPECT_EQ(cut.status, SolveStatus::kBudgetExhausted);
  EXPECT_EQ(cut.failure_reason, FailureReason::kBudgetExhausted);
  EXPECT_EQ(cut.attempts, 1);  // the retry did not start
  EXPECT_EQ(cut.counts, first.counts + init.units);
}

std::string WriteTemp(const std::string& name, const std::string& text) {
  return WriteTestFile("unwinding_retry_test_tmp", name, text);
}

// unwrap_chord.json on a 30-link geometry at 720° drawn by `make_unwrap_geometries.py
// --tuning-count 48` (its tuning_46, not shipped): the rollout attempt and the retry from the
// plain unwinding path both go round the pole's end; the retry that unwinds off the pole's line
// and then reaches solves it.
std::unique_ptr<Scenario> Tuning46() {
  const std::string file = WriteTemp("tuning_46_arm30.json", R"({"name": "tuning_46_arm30",
    "split": "tuning", "pole_tilt_deg": [14.05, -1.87], "pole_radius": 0.0358,
    "pole_translation": [-0.0323, 0.0, 0.0484], "target_offset": [-0.0951, 0.0293, -0.0167],
    "arm": {"urdf": ")" + kAssets + R"(robots/arm30_sdh.urdf",
            "disabled_groups": [["sdh_", "arm_link_30"]]}})");
  ScenarioSpec spec = ParseScenarioSpec(kChord);
  ApplyUnwrapGeometry(ReadUnwrapGeometry(file), &spec);
  return SetUpScenario(spec, 720.0);
}

// A plain unwinding path that passes the pole's line round its end (a whole turn of winding in one
// step) and ends far (> 1 m) from the reach target.
void ExpectRoundThePolesEndAndFarFromTheTarget(const PlanVerdict& plain) {
  EXPECT_GT(plain.max_winding_jump_turns, 0.5);   // a whole turn: across the line
  EXPECT_GT(plain.winding_jumps.beyond_ends, 0);  // round the pole's end
  EXPECT_GT(plain.reach_error_m, 1.0);
}

// An init's line-clearance (and winding) segment tests are charged as pair tests, not as FCL
// calls; its only collision queries are its configurations.
void ExpectLineTestsChargedAsPairTests(const internal::InitCounts& counts) {
  EXPECT_EQ(counts.collision_queries, counts.units.state_queries);
  EXPECT_LT(counts.narrow_phase_calls, counts.units.pair_tests());
}

// The init of "unwinding_then_reach": it starts at q0, unwinds without passing the pole's line
// (the plain unwinding path passes it, round the pole's end: a whole turn of winding in one small
// step) and ends with the hand at the reach target, where the plain path ends 2.8 m from it. The
// writhe is held by a cost while the hand moves, and drifts (to 0.25 here; AICO aims it at the
// writhe task's target).
TEST(UnwindingRetry, TheReachInitUnwindsOffThePoleLineThenReaches) {
  const auto s = Tuning46();
  const Eigen::VectorXd& q0 = s->initial.problem.q0;
  internal::InitCounts plain_counts, counts;
  const Trajectory plain = internal::UnwindingInit(*s, s->initial, q0, AicoInit::kUnwinding,
                                                   s->initial.problem, &plain_counts);
  const Trajectory init = internal::UnwindingInit(*s, s->initial, q0, AicoInit::kUnwindingThenReach,
                                                  s->initial.problem, &counts);
  ASSERT_EQ(init.num_points(), s->spec.problem.num_steps + 1);
  EXPECT_TRUE(init.q.col(0).isApprox(q0, 1e-12));
  // The judge walks both paths at the check resolution.
  const PlanVerdict plain_verdict = JudgePlan(*s, plain);
  const PlanVerdict verdict = JudgePlan(*s, init);
  ExpectRoundThePolesEndAndFarFromTheTarget(plain_verdict);
  EXPECT_LT(verdict.max_winding_jump_turns, 0.5);
  EXPECT_LT(verdict.reach_error_m, 0.01);
  ExpectLineTestsChargedAsPairTests(counts);
}

// The init is built for the attempt's problem: a task switched off (an ablation) is left out. With
// the reach off, the init is the line-cleared unwinding alone (the hand stays where it ends, far
// from the target, and the reach continuation's estimates, at least one per 0.05 m plus 5, are
// not spent); with the line clearance off too, it is the plain unwinding path.
TEST(UnwindingRetry, TheReachInitLeavesOutTasksSwitchedOff) {
  const auto s = Tuning46();
  const Eigen::VectorXd& q0 = s->initial.problem.q0;
  const auto init = [&](AicoInit kind, const std::vector<std::string>& off,
                        internal::InitCounts* counts) {
    MotionProblem p = AttemptProblem(*s, s->initial, 0);
    DisableTasks(off, &p);
    return internal::UnwindingInit(*s, s->initial, q0, kind, p, counts);
  };
  internal::InitCounts all, no_reach, none, plain;
  const Trajectory full = init(AicoInit::kUnwindingThenReach, {}, &all);
  const Trajectory unreached = init(AicoInit::kUnwindingThenReach, {"reach"}, &no_reach);
  const double left =
      CheckEndState(*s, unreached.q.col(unreached.num_points() - 1), false).reach_error_m;
  EXPECT_GT(left, 1.0);
  EXPECT_LT(CheckEndState(*s, full.q.col(full.num_points() - 1), false).reach_error_m, 0.01);
  EXPECT_GE(all.units.state_queries - no_reach.units.state_queries,
            static_cast<long>(std::ceil(left / 0.05)) + 5);
  const Trajectory bare = init(AicoInit::kUnwindingThenReach, {"reach", "off_pole_line"}, &none);
  EXPECT_TRUE(bare.q.isApprox(init(AicoInit::kUnwinding, {}, &plain).q, 1e-12));
  EXPECT_EQ(none.units, plain.units);
  // The problem pairs with the scenario's tasks by index.
  MotionProblem short_problem = AttemptProblem(*s, s->initial, 0);
  short_problem.tasks.pop_back();
  EXPECT_THROW(
      internal::UnwindingInit(*s, s->initial, q0, AicoInit::kUnwinding, short_problem, &plain),
      std::logic_error);
}

TEST(UnwindingRetry, AFailureOfBothEarlierAttemptsIsSolvedByTheReachInit) {
  const auto s = Tuning46();
  PlanRequest request;
  const PlanReport r = RunPlanner(*s, request).report;
  EXPECT_TRUE(r.success) << FailureReasonName(r.failure_reason);
  EXPECT_EQ(r.attempts, 3);
  // Without the third attempt the run fails: the same scenario with the plain retry only.
  ScenarioSpec spec = s->spec;
  spec.aico_attempts.resize(2);
  const auto two = SetUpScenario(spec, 720.0);
  const PlanReport r2 = RunPlanner(*two, request).report;
  EXPECT_FALSE(r2.success);
  EXPECT_EQ(r2.attempts, 2);
  EXPECT_LT(r2.counts.state_queries, r.counts.state_queries);
}

// unwrap_chord.json on tuning_17 (12-link arm, moved pole) at 540°: the first three attempts end
// short of the end conditions (the arm's spare length curled near the target, its writhe or reach
// missed); the fourth, from the plain unwinding path with the collision cost weakened and the
// writhe and reach costs strengthened, solves it.
std::unique_ptr<Scenario> Tuning17(int attempts) {
  return ShippedTuning("tuning_17_arm12", 540.0, attempts);
}

TEST(UnwindingRetry, AFailureOfThreeAttemptsIsSolvedByTheWeakerCollisionCost) {
  const auto s = Tuning17(4);
  const auto index = [&](const std::string& name) {
    for (size_t i = 0; i < s->spec.tasks.size(); ++i) {
      if (s->spec.tasks[i].name == name) return static_cast<Eigen::Index>(i);
    }
    ADD_FAILURE() << "no task " << name;
    return Eigen::Index{0};
  };
  const Eigen::Index collision = index("collision"), writhe = index("writhe"),
                     reach = index("reach");
  const Eigen::VectorXd& scale = s->aico_attempts[3].precision_scale;
  EXPECT_DOUBLE_EQ(scale[collision], 0.2);
  EXPECT_DOUBLE_EQ(scale[writhe], 10.0);
  EXPECT_DOUBLE_EQ(scale[reach], 10.0);
  EXPECT_EQ((scale.array() != 1.0).count(), 3);
  // Every slice's precision is scaled, the final ones too.
  const MotionProblem p0 = AttemptProblem(*s, s->initial, 0),
                      p3 = AttemptProblem(*s, s->initial, 3);
  EXPECT_TRUE(p3.tasks[collision].precision.isApprox(0.2 * p0.tasks[collision].precision));
  EXPECT_TRUE(p3.tasks[reach].precision.isApprox(10.0 * p0.tasks[reach].precision));
  PlanRequest request;
  const PlanReport four = RunPlanner(*s, request).report;
  EXPECT_TRUE(four.success) << FailureReasonName(four.failure_reason);
  EXPECT_EQ(four.attempts, 4);
  const PlanReport three = RunPlanner(*Tuning17(3), request).report;
  EXPECT_FALSE(three.success);
  EXPECT_EQ(three.attempts, 3);
}

// The plain unwinding path depends on the start alone: an attempt that starts from it again
// reuses it, and is charged its own AICO sweeps only. Here a repeat of attempt 1 (the same init,
// the same problem: the same sweeps) costs what attempt 1 cost without its continuation.
TEST(UnwindingRetry, ThePlainUnwindingPathIsMadeAndChargedOnce) {
  const auto one = Tuning17(2);
  ScenarioSpec spec = one->spec;
  spec.aico_attempts.resize(3);
  spec.aico_attempts[2] = spec.aico_attempts[1];
  const auto repeat = SetUpScenario(spec, 540.0);
  PlanRequest request;
  request.aico_retry = false;
  const PlanReport r0 = RunPlanner(*one, request).report;
  request.aico_retry = true;
  const PlanReport r1 = RunPlanner(*one, request).report;
  const PlanReport r2 = RunPlanner(*repeat, request).report;
  ASSERT_FALSE(r1.success);
  ASSERT_FALSE(r2.success);
  EXPECT_EQ(r1.attempts, 2);
  EXPECT_EQ(r2.attempts, 3);
  internal::InitCounts init;
  internal::UnwindingInit(*one, one->initial, one->initial.problem.q0, AicoInit::kUnwinding,
                          one->initial.problem, &init);
  EXPECT_GT(init.units.state_queries, 0);
  EXPECT_EQ(r2.counts + r0.counts + init.units, r1.counts + r1.counts);
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

// unwrap_chord.json on tuning_10 (30-link arm, pole tilted and moved) at 720°: the first four
// attempts fail (the last of them passing the pole's line); the fifth, from the winding
// continuation, solves it.
std::unique_ptr<Scenario> Tuning10(int attempts) {
  return ShippedTuning("tuning_10_arm30", 720.0, attempts);
}

// The init of "winding_then_reach" steps the winding about the pole's line to 0: it starts at q0
// two turns round the line, neither it nor the reach after it passes the line, and the hand ends
// 0.03 m from its target. The plain writhe continuation passes the line round the pole's end (a
// whole turn in one step) and ends 2 m from the target; kept off the line, it stalls and the
// reach after it ends 0.25 m from the target.
TEST(UnwindingRetry, TheWindingInitUnwindsWithoutPassingThePolesLine) {
  const auto s = Tuning10(5);
  const Eigen::VectorXd& q0 = s->initial.problem.q0;
  const auto init = [&](AicoInit kind, internal::InitCounts* counts) {
    return internal::UnwindingInit(*s, s->initial, q0, kind, s->initial.problem, counts);
  };
  internal::InitCounts plain_counts, line_counts, counts;
  const PlanVerdict plain = JudgePlan(*s, init(AicoInit::kUnwinding, &plain_counts));
  const PlanVerdict line = JudgePlan(*s, init(AicoInit::kUnwindingThenReach, &line_counts));
  const Trajectory path = init(AicoInit::kWindingThenReach, &counts);
  ASSERT_EQ(path.num_points(), s->spec.problem.num_steps + 1);
  EXPECT_TRUE(path.q.col(0).isApprox(q0, 1e-12));
  EXPECT_GT(std::abs(ReportWinding(*s, q0)), 1.9);
  const PlanVerdict verdict = JudgePlan(*s, path);
  ExpectRoundThePolesEndAndFarFromTheTarget(plain);
  EXPECT_LT(line.max_winding_jump_turns, 0.1);
  EXPECT_GT(line.reach_error_m, 0.2);
  EXPECT_LT(verdict.max_winding_jump_turns, 0.1);
  EXPECT_LT(verdict.reach_error_m, 0.05);
  // Unwound: no turn left round the pole (the end condition's chord-closed winding).
  EXPECT_LT(std::abs(verdict.final_winding_turns), 0.1);
  // Its winding evaluations are charged: the continuation's winding task in each pose
  // estimate, and each reading of the winding after one, a state query of its own (no
  // collision query). Per state query it makes more pair tests besides FCL's than the
  // writhe continuation kept off the line, whose only such tests are the line-clearance
  // task's 30 segments.
  ExpectLineTestsChargedAsPairTests(line_counts);
  EXPECT_GT(counts.units.state_queries, counts.collision_queries);
  const auto per_query = [](const internal::InitCounts& c) {
    return static_cast<double>(c.units.pair_tests() - c.narrow_phase_calls) /
           static_cast<double>(c.units.state_queries);
  };
  EXPECT_GT(per_query(counts), per_query(line_counts) + 10.0);
}

TEST(UnwindingRetry, AFailureOfFourAttemptsIsSolvedByTheWindingInit) {
  PlanRequest request;
  const PlanReport four = RunPlanner(*Tuning10(4), request).report;
  EXPECT_FALSE(four.success);
  EXPECT_EQ(four.failure_reason, FailureReason::kTunnelled);
  EXPECT_EQ(four.attempts, 4);
  const PlanReport five = RunPlanner(*Tuning10(5), request).report;
  EXPECT_TRUE(five.success) << FailureReasonName(five.failure_reason);
  EXPECT_EQ(five.attempts, 5);
  EXPECT_GT(five.counts.state_queries, four.counts.state_queries);
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
              "aico.retry.init: unknown AICO init 'rollout' (unwinding, unwinding_then_reach, "
              "winding_then_reach)");
  ExpectError("bad_init_1.json", Mini(report, R"({"retry": [{}, {"init": "rollout"}]})"),
              "aico.retry[1].init: unknown AICO init 'rollout'");
  ExpectError("empty.json", Mini(report, R"({"retry": []})"),
              "aico.retry: expected at least one retry");
  ExpectError("number.json", Mini(report, R"({"retry": 3})"),
              "aico.retry: expected an object or an array of objects");
  ExpectError("no_report_2.json", Mini("", R"({"retry": [{"init": "unwinding_then_reach"}]})"),
              "aico.retry[0].init: the unwinding inits follow the writhe_report pair");
  ExpectError("no_report.json", Mini("", R"({"retry": {"init": "unwinding"}})"),
              "aico.retry.init: the unwinding inits follow the writhe_report pair");
  // The winding init needs a line: a closed object chain (a ring's loop) has none.
  const std::string ring =
      R"(, {"name": "ring", "urdf": ")" + kAssets + R"(objects/ring.urdf", "xyz": [0.5, 0, 0.8]})";
  std::string loop = Mini(R"( "writhe_report": {"chain": "arm", "object": "ring",
      "object_chain": "loop"},)",
                          R"({"retry": [{}, {"init": "winding_then_reach"}]})");
  loop.insert(loop.find("}],") + 1, ring);
  ExpectError("loop.json", loop,
              "aico.retry[1].init: \"winding_then_reach\" winds the arm about the line through the "
              "ends of the writhe_report's object chain, and its ends coincide");
  const auto s = SetUpScenario(
      ParseScenarioSpec(WriteTemp("ok.json", Mini(report, R"({"retry": {"init": "unwinding"}})"))));
  ASSERT_EQ(s->aico_attempts.size(), 2u);
  EXPECT_TRUE(s->aico_attempts[0].init == AicoInit::kDefault);
  EXPECT_TRUE(s->aico_attempts[1].init == AicoInit::kUnwinding);
  // An array: one attempt per entry, in order; an entry without "init" starts as attempt 0.
  const auto a = SetUpScenario(ParseScenarioSpec(WriteTemp(
      "array.json",
      Mini(
          report,
          R"({"max_iterations": 7, "retry": [{"init": "unwinding_then_reach"}, {"max_iterations": 3}]})"))));
  ASSERT_EQ(a->aico_attempts.size(), 3u);
  EXPECT_TRUE(a->aico_attempts[1].init == AicoInit::kUnwindingThenReach);
  EXPECT_EQ(a->aico_attempts[1].max_iterations, 7);
  EXPECT_TRUE(a->aico_attempts[2].init == AicoInit::kDefault);
  EXPECT_EQ(a->aico_attempts[2].max_iterations, 3);
}

}  // namespace
}  // namespace planning
