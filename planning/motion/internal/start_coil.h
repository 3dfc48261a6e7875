// Private: the writhe continuations of the scenario set-up (scenario_setup.cc): the coil start,
// the unwrapped goal init and the unwinding path (see "Start coil" in scenario.h).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/motion/scenario.h"
#include "planning/motion/trajectory.h"

namespace planning::internal {

// From `from` (size n) toward total writhe `target` (turns, of the scenario's writhe_report pair)
// in steps of `step` turns: damped Gauss–Newton final-pose estimates under a writhe task, a soft
// collision task with `margin` (m) and a joint-limit task, until the writhe is within 0.005 of
// `target` or stops moving. Every accepted configuration (from included) is appended to `path`
// if not null. Returns the last configuration (n). In the scenario's initial world.
Eigen::VectorXd WritheContinuation(const Scenario& s, const Eigen::VectorXd& from, double target,
                                   double step, double margin,
                                   std::vector<Eigen::VectorXd>* path = nullptr);

// `path` (at least one configuration of size n) resampled at num_points equally spaced
// joint-space arc lengths (linear between its configurations): n × num_points.
Eigen::MatrixXd ResampleByArcLength(const std::vector<Eigen::VectorXd>& path, int num_points);

// What an unwinding init spent: its cost units (every configuration its pose estimates evaluate
// is one state query; pair tests of its collision and line-clearance tasks), and of them its
// collision task's queries and FCL shape-pair calls (a report's collision_checks and
// narrow_phase_calls).
struct InitCounts {
  QueryCounts units;
  long collision_queries = 0;
  long narrow_phase_calls = 0;
};

// The init of an AICO attempt whose aico.retry "init" is `kind` (not kDefault), from q0 (size n) in
// `world`, for the attempt's `problem` (one task per scenario task; a task of precision 0 at every
// slice is switched off):
//   kUnwinding: the writhe continuation from q0 to total writhe 0 (as WritheContinuation, with the
//     step and margin of the scenario's start spec);
//   kUnwindingThenReach: the same continuation also under the problem's line-clearance tasks
//     (target 0, at their largest precision in `problem`), then a reach continuation: every order-0
//     position task with a final precision ρ_T > 0 has its point moved in a straight line to its
//     final target y*_T, at most 0.05 m per pose estimate (precision 1000) and 5 more estimates at
//     the targets, under the writhe held where the unwinding ended, the collision and joint-limit
//     costs and the line-clearance tasks.
//   kWindingThenReach: as kUnwindingThenReach, with the first continuation stepping the winding of
//     the report chain about the report object's line (ReportWinding, a winding task instead of the
//     writhe task) to 0 in steps of the start spec's step (turns). Its gradient moves the chain's
//     free end round the line (the inner points' terms cancel, topology/winding.h), so it unwinds
//     a coil from the hand back rather than sliding it along the pole and off its end, as the
//     writhe's pull can near the end of a long arm.
// `problem`'s tasks pair with world.tasks by index (one per spec, as AttemptProblem builds them).
// The path is resampled by ResampleByArcLength to T + 1 slices, dt = duration / T. Adds what it
// spent to *counts. Throws std::logic_error when problem and world.tasks differ in size.
Trajectory UnwindingInit(const Scenario& s, const ScenarioState& world, const Eigen::VectorXd& q0,
                         AicoInit kind, const MotionProblem& problem, InitCounts* counts);

// The start coil: WritheContinuation from `from` to `target`, made a state the robot can be in
// (collision-free, inside the joint limits) and a coil about the pole's line (no segment within
// `margin` of the report object's line beyond its ends), retried from seeded perturbations when
// it is not or stops short (start_coil.cc says how). Sets *collides when no collision-free start
// was found, *near_line when the start is within `margin` of the line beyond the ends.
// Deterministic.
Eigen::VectorXd StartCoil(const Scenario& s, const Eigen::VectorXd& from, double target,
                          double step, double margin, bool* collides, bool* near_line);

// True if the robot at q (size n) touches neither itself nor the scenario's initial objects.
bool CollisionFree(const Scenario& s, const Eigen::VectorXd& q);

}  // namespace planning::internal
