// Receding-horizon re-planning when an object of a scenario moves (the thesis' "dynamic
// environment"): the arm executes its current AICO plan while the object follows a path; every
// re-plan period AICO re-plans from the current state, warm-started with the previous solution.
//
// Time: plan time t in seconds, slices of τ = duration / T (scenario.h). Execution covers the
// scenario's slices g = 0..T (t = g·τ). Let k = max(1, round(min(replan_period_s / τ, T)))
// slices. At g = 0 the object is placed at path(0) and the full problem is solved (the
// scenario's AICO options, cold start as configured). At g = k, 2k, ... < T:
//   1. the object is moved to path(g·τ) (MoveObject; it stays there until the next re-plan);
//   2. the window problem is the scenario's problem shifted by g slices: same T and τ, start
//      (q, q̇) = the executed state at g, targets and precisions y*'_j = y*_{min(g+j, T)},
//      ρ'_j = ρ_{min(g+j, T)} (past the end: hold the final targets);
//   3. AICO runs at most `sweeps` sweeps from init q'_j = q^{prev}_{min(g−g_prev+j, T)} (the
//      previous plan shifted by the elapsed slices, padded with its last configuration).
// The executed trajectory takes slices g_prev..g of each plan. Between re-plans the object does
// not move, so each executed segment [g_i, g_{i+1}] is judged (planner.h JudgePlan) with the
// object where it was; the last segment's verdict also carries the end criteria.
//
// Targets attached to the moving object (AttachedTasks): a task aims at a world-space point when
// it is a "box" task (its centre), a "position" task (its targets y*_t) or a "winding" task (its
// axis point). Such a task belongs to the object whose frame origin is nearest to that point
// (box centre, y*_T, axis point; ties: the first object in spec order) and moves with it: when
// the object moves by δ, the point moves by δ (every slice of a position target). Writhe and
// winding values are relative (unchanged when the robot chain and the object move together), so
// a writhe target stays as it is while its feature reads the object chain where the object is
// now; joint-space, limit and collision tasks have no point. ReplanOptions::attached_tasks names
// the attached tasks explicitly instead. Everything above (the window's targets, the verdicts,
// the viewer's `move`) uses the moved targets.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "planning/motion/aico.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/trajectory.h"

namespace planning {

// Position of an object over plan time: p(t), linear between samples, constant before the first
// and after the last sample.
struct ObjectPath {
  std::vector<double> t;           // seconds, strictly increasing, at least one sample
  std::vector<Eigen::Vector3d> p;  // world position of the object's frame, m (size = t)
};

// Reads a CSV path: a header line "t,x,y,z", then one row "t,x,y,z" per sample (seconds, m).
// Blank lines are skipped. Throws std::invalid_argument "FILE:LINE: ..." for a wrong header, a
// row without exactly four numbers, a non-finite value or a time not greater than the previous
// one, and "FILE: ..." for a missing file or one without samples.
ObjectPath ReadObjectPath(const std::string& path);

// p(t) (see ObjectPath). Requires a non-empty path.
Eigen::Vector3d ObjectPositionAt(const ObjectPath& path, double t);

// One re-plan.
struct ReplanStep {
  int slice = 0;        // g: executed slice at which it re-planned
  double time_s = 0.0;  // g·τ
  Eigen::Vector3d object_position = Eigen::Vector3d::Zero();
  int sweeps = 0;  // AICO sweeps run (accepted + rejected)
  SolveStatus status = SolveStatus::kMaxIterations;
  double cost = 0.0;           // the window plan's AICO cost
  double wall_ms = 0.0;        // wall-clock time of the re-plan (move + window + AICO), ms
  double cpu_ms = 0.0;         // CPU time of this thread for the same, ms
  long collision_queries = 0;  // narrow-phase queries of its collision feature
};

struct ReplanOptions {
  double replan_period_s = 0.1;  // plan time between re-plans; rounded to k >= 1 slices of τ
  int sweeps = 3;                // AICO sweep budget of each re-plan (max_iterations)
  // AICO options of the re-plans other than max_iterations: the scenario's attempt-0 options.
  // damping < 0: keep the scenario's initial λ.
  double damping = -1.0;
  // false: each re-plan starts from the current state repeated (cold start), for comparison.
  bool warm_start = true;
  // Names of the tasks whose world-space points move with the object; unset: AttachedTasks.
  std::optional<std::vector<std::string>> attached_tasks;
  // Called after every re-plan (progress; may throw to stop the run, the scenario is restored).
  std::function<void(const ReplanStep& step)> on_replan;
  // Called after every AICO sweep of a re-plan (the viewer's progress and Cancel; may throw).
  AicoCallback on_sweep;
};

struct ReplanResult {
  Trajectory executed;                            // T+1 slices 0..T, dt = τ
  std::vector<Eigen::Vector3d> object_positions;  // per executed slice (size T+1), m
  int object = -1;        // index into scenario.objects of the moving object
  int period_slices = 1;  // k
  double period_s = 0.0;  // k·τ
  AicoResult initial;     // the full solve at g = 0
  double initial_wall_ms = 0.0;
  double initial_cpu_ms = 0.0;
  std::vector<ReplanStep> replans;  // in order; count = replans.size()
  PlanVerdict verdict;              // executed path (see above): collision, limits, end criteria
  // Total writhe of the report pair at the first / last executed slice, the object where it was
  // then (0 without a report pair).
  double start_writhe_total = 0.0, final_writhe_total = 0.0;
  // The report chain passes through the report object's loop at the end
  // (ChainSegmentThroughLoop, success.h); false when the report object chain is not a closed loop.
  // Required for success (kNotThroughLoop) when the moving object is the report loop.
  bool passed_through = false;
  bool success = false;  // verdict.ok(): JudgePlan found no failure reason
  // Re-plans per second of CPU time: replans.size() / Σ cpu_ms · 1000 (0 without re-plans).
  double rate_hz = 0.0;
  // Re-plans per second of wall-clock time: replans.size() / Σ wall_ms · 1000 (0 without).
  double wall_rate_hz = 0.0;
  double median_cpu_ms = 0.0, max_cpu_ms = 0.0;  // over the re-plans
  double median_wall_ms = 0.0, max_wall_ms = 0.0;
};

// Indices into scenario.problem.tasks of the tasks attached to object `object` by the rule
// above (the scenario as it is now). Throws std::invalid_argument for an unknown object.
std::vector<int> AttachedTasks(const Scenario& scenario, const ScenarioState& state,
                               const std::string& object);
// The indices of options.attached_tasks (task names), or AttachedTasks when unset. Throws
// std::invalid_argument for an unknown task name, listing the valid ones.
std::vector<int> ResolveAttachedTasks(const Scenario& scenario, const ScenarioState& state,
                                      const std::string& object, const ReplanOptions& options);

// MoveObject(scenario, object, position) with the world-space points of tasks `attached`
// (indices into scenario.problem.tasks) moved by the same δ = position − old position: box
// centres and winding axis points in scenario.spec (the features are rebuilt from it) and the
// targets y*_t (all slices) of position tasks in scenario.problem. Throws as MoveObject, and
// std::invalid_argument for an index out of range.
void MoveObjectWithTargets(const Scenario& scenario, ScenarioState* state,
                           const std::string& object, const Eigen::Vector3d& position,
                           const std::vector<int>& attached);

// Buffers of the re-plans of one scenario, made once: the window problem, the AICO workspace and
// the init.
struct ReplanWorkspace {
  ReplanWorkspace(const Scenario& scenario, const ScenarioState& state);
  MotionProblem window;  // what AICO solves; its features follow MoveObject (see Replan)
  AicoWorkspace aico;
  Trajectory init;  // n × (T+1), dt = τ
};

// One receding-horizon re-plan (steps 2–3 above) for a custom loop: rebuilds the window's
// features and their collision data from the scenario as it is now (call it after
// MoveObjectWithTargets), shifts the targets of scenario.problem (as moved) by `slice` g >= 0,
// starts at (q, q̇) (sizes n), and runs AICO for options.sweeps sweeps from `previous` (n × (T+1),
// the last plan) shifted by `shift` >= 0 columns and padded with its last column
// (options.warm_start), else from q repeated. The scenario's attempt-0 AICO options with
// max_iterations = sweeps (and options.damping if >= 0); options.on_sweep after each sweep.
// Throws std::invalid_argument for negative slice/shift or wrong sizes.
AicoResult Replan(const Scenario& scenario, const ScenarioState& state, int slice,
                  const Eigen::VectorXd& q,
                  const Eigen::VectorXd& qdot, const Eigen::MatrixXd& previous, int shift,
                  const ReplanOptions& options, ReplanWorkspace* ws);

// The plan a receding-horizon loop executes: configurations and velocities and the scenario
// slice g0 of its column 0 (column j is executed at slice g0 + j).
struct RecedingPlan {
  Eigen::MatrixXd q;     // n × (T+1)
  Eigen::MatrixXd qdot;  // n × (T+1)
  int start_slice = 0;   // g0
};
// A plan from a trajectory (n × (T+1)) and its velocities; empty velocities: finite differences
// q̇_t = (q_{t+1} − q_t)/τ, last 0. Throws std::invalid_argument for mismatched sizes.
RecedingPlan MakeRecedingPlan(const Trajectory& trajectory, const Eigen::MatrixXd& velocities,
                              int start_slice);

// One step of the loop, what RunReplanning does at every re-plan and the viewer's `move` does
// once, after the caller moved the object and its attached tasks (MoveObjectWithTargets): after
// executing `elapsed` slices of `plan` (0 <= elapsed <= T; the state is its column `elapsed`),
// re-plans at slice g = plan.start_slice + elapsed from that state, warm-started with the plan
// shifted by `elapsed` (Replan). `plan` becomes the new plan (start_slice g). Returns the step
// (slice, time, sweeps, status, cost, wall and CPU time of the re-plan; object_position left 0);
// `result` receives the AICO result when not null. Reads the scenario only. Throws as Replan.
ReplanStep ReplanFrom(const Scenario& scenario, const ScenarioState& state, int elapsed,
                      const ReplanOptions& options, ReplanWorkspace* ws, RecedingPlan* plan,
                      AicoResult* result = nullptr);

// Runs the re-planning simulation above with object `object` of `scenario` (a name from
// ObjectNames) following `path`, its attached tasks (ResolveAttachedTasks) moving with it, in a
// ScenarioState of its own (MakeScenarioState; the scenario is not changed). The executed path is
// judged segment by segment by JudgePlan, the last segment also with through_loop when the moving
// object is the report loop. Throws std::invalid_argument for an unknown object name (listing the
// valid ones), an empty path or invalid options (replan_period_s not > 0 or not finite,
// sweeps < 1).
ReplanResult RunReplanning(const Scenario& scenario, const std::string& object,
                           const ObjectPath& path, const ReplanOptions& options = {});

// The plan report of a re-planning run (report.json of `plan --moving-object`): the executed
// path's verdict (success, failure reason and step, clearance, reach, winding), checks and
// iterations of the initial solve and every re-plan, their wall time.
PlanReport ReplanReport(const ReplanResult& result);

}  // namespace planning
