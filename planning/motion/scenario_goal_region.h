// The goal region of a scenario for the goal-region RRTs (planner.h "rrt-region", "birrt-region"):
// the same goal information AICO's success is judged by, instead of the one goal state q̂_T.
//
//   G = { q : CheckEndState(scenario, state, q, false).ok() }  (success.h: reach within the
//       position tolerance, box point inside its box, |final writhe| and |final winding| below
//       their bounds); validity (joint limits, collision) is the planner's counted check.
//   Sampler, one draw: up to K = scenario.rrt_goal.ik_starts times (rrt.goal_ik_starts, default
//       1): q_u uniform in the joint box of ScenarioRrtProblem (u = UniformUnit of the planner's
//       generator, one per dof); q̃ = SolveIk from the single start q_u (damped least squares
//       inside the joint limits, scenario.rrt_goal.ik_iterations iterations
//       (rrt.goal_ik_iterations, default 200), position tolerance kIkToleranceFraction × the
//       criterion's) toward the reach target y*_T of the position task and the centre of the box
//       task (whichever the criterion has; neither: q̃ = q_u); the draw ends at the first q̃ with
//       G(q̃) and returns it, else the K-th q̃ and false. Rejection: the planner keeps q̃ only if it
//       is also valid.
#pragma once

#include "planning/collision/collision.h"
#include "planning/motion/goal_region.h"
#include "planning/motion/scenario.h"

namespace planning {

inline constexpr double kIkToleranceFraction = 0.1;

// What the sampler spent, in the planner's cost units: the validity checks of its candidates
// (state queries and the pair tests behind them, read off the collision state the checker uses)
// and the process CPU time of its draws (uniform draw, IK, end conditions) and of those checks.
struct GoalSamplerCost {
  QueryCounts counts;
  double cpu_time_s = 0.0;
};

// The goal region of `scenario` in the world `state` (see the file comment). `valid` is the
// planner's validity checker on `coll` (planner.h ValidityChecker); the region's `valid` calls it
// and adds the counts of each call, and the sampler its CPU time, to *cost. `scenario`, `state`,
// `valid`, `coll` and `cost` must outlive the region. Throws std::invalid_argument when the
// success criterion has no end condition (no goal to sample).
GoalRegion ScenarioGoalRegion(const Scenario& scenario, const ScenarioState& state,
                              const ValidityFn& valid, const CollisionData& coll,
                              GoalSamplerCost* cost);

}  // namespace planning
