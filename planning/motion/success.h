// The one judge of success: whether a path meets a scenario's success criteria (JudgePlan) and
// the end conditions of one configuration (CheckEndState), with the reasons a plan fails. Every
// planner run (plan, bench, the re-planner, the viewer, Python) is judged here, the same way.
#pragma once

#include <Eigen/Core>

#include "planning/motion/scenario.h"
#include "planning/motion/trajectory.h"

namespace planning {

// Why a plan is not a success (kNone: it is one). See JudgePlan for the order of the checks.
enum class FailureReason {
  kNone,
  kJointLimits,       // a resampled state outside the joint limits (failure_step)
  kCollision,         // a resampled state in collision (failure_step)
  kTunnelled,         // winding jump >= max_jump between resampled states (failure_step and
                      // max_winding_jump_turns): through the pole, or off its end (with
                      // winding_tunnel_through_object_only: through the pole, or not located)
  kWritheNotReached,  // |final writhe| or |final winding| not below its bound
  kReachError,        // the position task's final distance (reach_error_m) above its tolerance,
                      // or the box task's value not 0
  kNotThroughLoop,    // through_loop: the report chain does not pass through the object's loop
  kBudgetExhausted,   // RRT: no path within the collision-check budget
  kDiverged,          // AICO: no accepted sweep / non-finite cost
  kInvalidInput,      // invalid start or goal
};
// "none" | "joint_limits" | "collision" | "tunnelled" | "writhe_not_reached" | "reach_error" |
// "not_through_loop" | "budget_exhausted" | "diverged" | "invalid_input".
const char* FailureReasonName(FailureReason reason);

// The end conditions of the success criteria at one configuration q (what JudgePlan checks at a
// path's last state) and, with `state_checks`, the state itself (joint limits, InCollision).
struct EndState {
  bool within_limits = true;   // (state_checks only)
  bool collision_free = true;  // (state_checks only)
  double writhe_total = 0.0;   // ReportWritheTotal(q)
  // ReportWinding(q), minus the chord's winding with winding_closed_by_chord (the chain closed by
  // the segment from its last point to its first: an integer up to rounding), in turns; with the
  // winding criterion only, else 0.
  double winding_turns = 0.0;
  // The writhe matrix entry of largest |W_ij| (row = robot chain segment, or the chord with
  // writhe_closed_by_chord; col = object segment; −1 and 0 when there is no report pair).
  int writhe_peak_row = -1, writhe_peak_col = -1;
  double writhe_peak_value = 0.0;
  bool writhe_reached = true;  // |writhe| < writhe_total_below, |winding| < winding_final_below
  double reach_error_m = -1.0;  // |φ(q) − y*_T| of the position task (−1: no position criterion)
  bool reached = true;          // reach_error_m <= position_tolerance, box point inside
  bool ok() const { return within_limits && collision_free && writhe_reached && reached; }
  // 0 when ok(); otherwise Σ of the relative excesses (|writhe|/bound, |winding|/bound,
  // reach/tolerance, 1 + box value) over the unmet conditions, + 1 per state check failed.
  double violation = 0.0;
};
// With the objects where `state` has them (the overload without a state: scenario.initial).
EndState CheckEndState(const Scenario& scenario, const ScenarioState& state,
                       const Eigen::VectorXd& q, bool state_checks);
EndState CheckEndState(const Scenario& scenario, const Eigen::VectorXd& q, bool state_checks);
// The same with the criteria `criteria` instead of scenario.success.
EndState CheckEndState(const Scenario& scenario, const ScenarioState& state,
                       const Eigen::VectorXd& q, bool state_checks,
                       const SuccessCriteria& criteria);

// The resampled steps whose winding jumps by at least winding_max_jump, by where the report chain
// passes the report object's line in that step (topology::LocateLineCrossings): within the object
// chain's extent (through the pole), only beyond its ends (round the end), or not located.
struct WindingJumps {
  int through_object = 0, beyond_ends = 0, unlocated = 0;
};

// The verdict of JudgePlan.
struct PlanVerdict {
  FailureReason reason = FailureReason::kNone;
  int step = -1;  // index into Densify(path, check_resolution) of the first violation, or −1
  double max_winding_jump_turns = 0.0;
  WindingJumps winding_jumps;        // (only with the winding criterion's max_jump)
  double final_winding_turns = 0.0;  // the end condition's winding (EndState::winding_turns)
  double final_writhe_total = 0.0;
  int writhe_peak_row = -1, writhe_peak_col = -1;  // see PlanReport
  double writhe_peak_value = 0.0;
  double reach_error_m = -1.0;   // −1 when the scenario has no position criterion
  double min_clearance_m = 0.2;  // minimum signed distance over the pairs within 0.2 m
  bool collision_free = true;    // every resampled state within limits and collision-free
  // Whether the report chain ends through the report object's closed loop (segment index of the
  // chain that crosses it, −1: none), evaluated whenever the report object chain is closed.
  bool loop_checked = false;
  bool passed_through = false;
  int through_segment = -1;
  // What the first violation was, in words: the joint and its value for kJointLimits ("joint
  // 'j4' = -3.1 outside [-3.07, -0.07]"), the pair for kCollision; empty otherwise.
  std::string detail;
  bool ok() const { return reason == FailureReason::kNone; }
};

// Judges `path` (non-empty) by the scenario's success criteria, the same for every planner
// (uncounted queries on a collision state of its own). The path is resampled with
// Densify(path, check_resolution); walking its states k = 0, 1, ...: outside the joint limits ->
// kJointLimits, InCollision -> kCollision, |w_k − w_{k−1}| >= winding_max_jump -> kTunnelled (w =
// ReportWinding, turns; only with the winding criterion; with winding_tunnel_through_object_only
// not when every pass of the line in that step lies beyond the object's ends); the first of these
// is the reason, except that a winding jump replaces a collision (the states passing through the
// pole collide; failure_step is then the jump's). At the end (CheckEndState of the last state): |w|
// >= winding_final_below (w of the chain closed by its chord with winding_closed_by_chord) or
// |total writhe| >= writhe_total_below -> kWritheNotReached; position error > position_tolerance or
// the box task's point outside its box (margin 0) -> kReachError; with through_loop, the report
// chain not through the report object's loop -> kNotThroughLoop. The one judge of success: `plan`,
// `bench`, the re-planner, the viewer and Python all use it. With the objects of `state` and the
// criteria `criteria` (the re-planner adds through_loop when the moving object is the report loop);
// the shorter overloads use scenario.initial and scenario.success.
PlanVerdict JudgePlan(const Scenario& scenario, const ScenarioState& state, const Trajectory& path,
                      const SuccessCriteria& criteria);
PlanVerdict JudgePlan(const Scenario& scenario, const ScenarioState& state, const Trajectory& path);
PlanVerdict JudgePlan(const Scenario& scenario, const Trajectory& path);

// The index k of the first segment [chain_k, chain_k+1] of `chain` (3 × N world points) that
// crosses the mean plane of the closed `loop` (3 × M, first point repeated at the end as in
// ChainPoints) at a point about which the loop winds at least half a turn
// (topology::PlanarWinding about the loop's Newell normal); −1 when none does.
int ChainSegmentThroughLoop(const Eigen::Matrix3Xd& chain, const Eigen::Matrix3Xd& loop);
// ChainSegmentThroughLoop(chain, loop) >= 0.
bool ChainThroughLoop(const Eigen::Matrix3Xd& chain, const Eigen::Matrix3Xd& loop);

// True when `loop` (3 × M) is closed: at least 4 columns, last = first (within 1e-9 m).
bool IsClosedLoop(const Eigen::Matrix3Xd& loop);

}  // namespace planning
