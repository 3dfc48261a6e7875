// AicoSolver: stepping one sweep at a time reproduces Solve() and SolveAico bit for bit (the
// trajectory, the cost history, the counters), the beliefs are readable between steps, and a
// Step after the end changes nothing.
#include <gtest/gtest.h>

#include <string>

#include "planning/motion/aico.h"
#include "planning/motion/scenario.h"

namespace planning {
namespace {

const std::string kScenarios = TOPOPLAN_SOURCE_DIR "/assets/scenarios/";

void ExpectSameResult(const AicoResult& a, const AicoResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.rejected, b.rejected);
  EXPECT_EQ(a.task_evaluations, b.task_evaluations);
  EXPECT_EQ(a.collision_queries, b.collision_queries);
  EXPECT_EQ(a.cost_history, b.cost_history);  // exact
  EXPECT_EQ(a.cost, b.cost);
  EXPECT_EQ(a.task_cost, b.task_cost);
  EXPECT_EQ(a.control_cost, b.control_cost);
  EXPECT_EQ(a.trajectory.dt, b.trajectory.dt);
  EXPECT_TRUE(a.trajectory.q == b.trajectory.q);  // bit for bit
  EXPECT_TRUE(a.velocities == b.velocities);
}

// Steps to the end, checking what is readable between steps; returns the final result.
AicoResult StepToEnd(const MotionProblem& problem, const AicoOptions& options) {
  AicoSolver solver(problem, options);
  EXPECT_EQ(solver.sweeps(), 0);
  EXPECT_EQ(solver.trajectory().num_points(), problem.num_steps + 1);
  int steps = 0;
  while (!solver.done()) {
    const double before = solver.cost();
    const AicoStep step = solver.Step();
    EXPECT_EQ(step.sweep, steps);
    ++steps;
    EXPECT_EQ(solver.sweeps(), steps);
    EXPECT_EQ(step.done, solver.done());
    if (step.accepted) {
      EXPECT_EQ(solver.cost(), step.cost);
    } else {
      EXPECT_EQ(solver.cost(), before);  // a rejected sweep restores the beliefs
    }
    if (!step.done) {
      EXPECT_EQ(step.status, SolveStatus::kMaxIterations);
    }
    EXPECT_EQ(solver.trajectory().num_points(), problem.num_steps + 1);
    EXPECT_EQ(solver.state().b.size(), static_cast<size_t>(problem.num_steps + 1));
    EXPECT_TRUE(solver.trajectory().q.col(problem.num_steps) ==
                solver.state().b[problem.num_steps].head(problem.q0.size()));
  }
  EXPECT_LE(steps, options.max_iterations);
  // A Step after the end is a no-op.
  const AicoResult end = solver.result();
  const AicoStep again = solver.Step();
  EXPECT_TRUE(again.done);
  EXPECT_EQ(again.status, end.status);
  EXPECT_EQ(solver.sweeps(), steps);
  ExpectSameResult(solver.result(), end);
  return end;
}

void CheckStepping(const MotionProblem& problem, const AicoOptions& options) {
  AicoWorkspace ws(problem);
  int calls = 0;
  const AicoResult one_shot =
      SolveAico(problem, options, &ws, [&](int, double, bool, const Trajectory&) { ++calls; });
  EXPECT_EQ(calls, one_shot.iterations);
  AicoSolver solver(problem, options);
  const AicoResult solved = solver.Solve();
  EXPECT_TRUE(solver.done());
  ExpectSameResult(solved, one_shot);
  ExpectSameResult(StepToEnd(problem, options), one_shot);
}

TEST(AicoStepping, UnwrapFrom720EqualsSolve) {
  ScenarioOverrides o;
  o.start_wrap_deg = 720.0;
  const auto s = LoadScenario(kScenarios + "unwrap.json", o);
  CheckStepping(s->initial.problem, s->aico);
}

// Small damping on the ring task: large first steps, so rejected sweeps are stepped through too.
TEST(AicoStepping, RingWithRejectionsEqualsSolve) {
  const auto s = LoadScenario(kScenarios + "reach_through_ring.json");
  AicoOptions options = s->aico;
  options.damping = 1e-4;
  options.max_iterations = 12;
  AicoWorkspace ws(s->initial.problem);
  const AicoResult r = SolveAico(s->initial.problem, options, &ws);
  EXPECT_GT(r.iterations, 0);
  CheckStepping(s->initial.problem, options);
}

TEST(AicoStepping, ZeroIterationsIsDoneAtOnce) {
  const auto s = LoadScenario(kScenarios + "reach_through_ring.json");
  AicoOptions options = s->aico;
  options.max_iterations = 0;
  AicoSolver solver(s->initial.problem, options);
  EXPECT_TRUE(solver.done());
  EXPECT_EQ(solver.Step().sweep, -1);
  EXPECT_EQ(solver.sweeps(), 0);
  AicoWorkspace ws(s->initial.problem);
  ExpectSameResult(solver.result(), SolveAico(s->initial.problem, options, &ws));
}

TEST(AicoStepping, BadInitThrows) {
  const auto s = LoadScenario(kScenarios + "reach_through_ring.json");
  Trajectory init;
  init.q.setZero(2, 3);
  EXPECT_THROW(AicoSolver(s->initial.problem, s->aico, &init), std::invalid_argument);
}

}  // namespace
}  // namespace planning
