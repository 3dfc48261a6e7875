// OMPL peer check of the RRT baselines (issue 5): OMPL's geometric RRT and RRTConnect run on the
// project's validity checker, edge resolution, goal and budget. Private to planning; compiled only
// when OMPL is found (TOPOPLAN_HAVE_OMPL). No OMPL or Boost type appears here.
#pragma once

#include <functional>

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

}  // namespace planning::internal
