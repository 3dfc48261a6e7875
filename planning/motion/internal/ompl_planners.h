// OMPL peer check of the RRT baselines (issue 5): OMPL's geometric RRT and RRTConnect run on the
// project's validity checker, edge resolution, goal and budget. Private to planning; compiled only
// when OMPL is found (TOPOPLAN_HAVE_OMPL). No OMPL or Boost type appears here.
#pragma once

#include <functional>

#include "planning/motion/goal_region.h"
#include "planning/motion/rrt.h"

namespace planning::internal {

enum class OmplPlanner { kRrt, kRrtConnect };

// Plans from problem.start to problem.goal in the box [lower, upper] (n = num_dofs) with OMPL:
//  - space: RealVectorStateSpace(n) with those bounds; the maximum extent is the box diagonal D,
//    so the motion-validator fraction is resolution / D (edge of length d: its end state and the
//    ⌈d/resolution⌉ − 1 interior states are checked, end state first — the states of rrt.h's
//    rule; OMPL visits the interior ones in bisection order, so an invalid edge may be rejected
//    after a different number of checks than in rrt.h);
//  - range = options.range (<= 0: 0.2 D), resolution = options.resolution (<= 0: 0.01 D);
//  - RRT: goal bias options.goal_bias; RRTConnect has no bias parameter;
//  - `valid` is called once per checked state; when options.max_checks calls have been made the
//    checker answers "invalid" without calling `valid` and the termination condition stops the
//    run (status kBudgetExhausted); also stops after options.max_iterations evaluations of the
//    termination condition;
//  - goal reached when a tree node is within 1e-9 (joint-space distance) of the goal; only exact
//    solutions count, no simplification (the returned path is the tree path);
//  - OMPL's global seed generator is reset to seed + 1 (OMPL rejects 0) before anything random is
//    created, and its console output is switched off: same seed, same result.
// result.iterations = evaluations of the termination condition (≈ OMPL iterations);
// result.tree_size is not reported (0). Throws std::invalid_argument like PlanRrt.
// `stop`, if given, is polled with the termination condition; true ends the run (kBudgetExhausted
// unless solved), e.g. a CPU-time budget.
RrtResult PlanOmpl(OmplPlanner planner, const RrtProblem& problem, const RrtOptions& options,
                   const ValidityFn& valid, unsigned seed, const std::function<bool()>& stop = {});

// The same with a goal region (goal_region.h) instead of one goal state: the OMPL peers of
// "rrt-region" / "birrt-region". The goal is an ob::GoalSampleableRegion whose isSatisfied is
// problem.goal.contains; goal candidates come from problem.goal.sample with a std::mt19937 seeded
// with `seed` (separate from OMPL's generator). OMPL's own rules then apply:
//  - RRT steers toward a goal sample on goal-biased iterations and succeeds when a new node
//    satisfies the goal. Its goal samples follow OMPL's GoalLazySamples: each call draws one
//    candidate while fewer than options.max_goal_states goal states are kept, keeps it when it is
//    in G and the counted checker accepts it, and returns the kept states in turn (a uniform state
//    of the box while none is kept).
//  - RRTConnect roots goal trees at valid goal samples (PlannerInputStates::nextGoal checks
//    bounds and validity through the counted checker, as long as OMPL's rule asks for more;
//    max_goal_states does not cap them);
//    each sample is the first in G of up to kOmplGoalDraws fresh candidates, or a state outside
//    the box (skipped by nextGoal) when none was.
// The check of a goal candidate calls problem.goal.valid when set (it must answer as `valid`; the
// scenario's books the cost to the goal sampler), every other check `valid`. result.goal: draws =
// candidates drawn, in_region = those in G, samples = goal states handed to the planner.
// Draws are capped by the budget: the run ends (kBudgetExhausted) once options.rrt.max_checks
// candidates were drawn, so a region the sampler cannot hit (RRTConnect waits for a goal tree
// and a candidate outside G costs no check) still ends.
inline constexpr int kOmplGoalDraws = 8;
RrtResult PlanOmplRegion(OmplPlanner planner, const GoalRegionProblem& problem,
                         const GoalRegionOptions& options, const ValidityFn& valid, unsigned seed,
                         const std::function<bool()>& stop = {});

}  // namespace planning::internal
