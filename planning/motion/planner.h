// Running a planner on a set-up scenario: one runner shared by the `plan` and `bench` commands,
// the tests and the benchmarks; the success criteria and the report metrics.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "planning/motion/aico.h"
#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/motion/rrt.h"
#include "planning/motion/scenario.h"
#include "planning/motion/success.h"
#include "planning/motion/trajectory.h"

namespace planning {

// kOmplRrt / kOmplRrtConnect: OMPL's geometric RRT (goal bias from the scenario, 0.1) and
// RRTConnect as a peer check of the project's RRTs, on the same checker, counter, budget, goal and
// edge resolution (only when built with OMPL, see OmplAvailable).
enum class Planner { kAico, kRrt, kBiRrt, kOmplRrt, kOmplRrtConnect };

// The registry: every planner of this build, in order ("aico", "rrt", "birrt", and
// "ompl-rrt", "ompl-rrtconnect" when built with OMPL).
std::vector<Planner> AvailablePlanners();
// "aico" | "rrt" | "birrt" | "ompl-rrt" | "ompl-rrtconnect"; throws std::invalid_argument for an
// unknown name (listing the valid ones), and for the OMPL names when built without OMPL
// ("... built without OMPL ...").
Planner ParsePlanner(const std::string& name);
// True when this build includes OMPL (libompl-dev was found by CMake).
bool OmplAvailable();
const char* PlannerName(Planner planner);

struct PlanReport {
  std::string planner;
  bool success = false;
  SolveStatus status = SolveStatus::kMaxIterations;
  long collision_checks = 0;    // configuration-level collision queries (thesis unit)
  long narrow_phase_calls = 0;  // FCL shape-pair calls behind them
  long iterations = 0;          // AICO sweeps (all attempts) / RRT iterations
  int attempts = 1;             // AICO: attempts run (2 when the scenario's retry ran)
  double cost = 0.0;            // AICO: final total cost; RRT: joint-space path length
  double path_length = 0.0;     // joint-space path length (rad)
  double time_s = 0.0;          // wall-clock planning time (the only non-deterministic field)
  double start_writhe_total = 0.0;
  double final_writhe_total = 0.0;
  double min_clearance_m = 0.0;  // minimum signed distance along the path at check_resolution
  bool path_collision_free = false;
  std::vector<double> cost_history;  // AICO accepted-sweep costs (last attempt)
  FailureReason failure_reason = FailureReason::kNone;
  int failure_step = -1;                // resampled-state index of the first violation, or −1
  double reach_error_m = -1.0;          // final distance of the position task to its target, m
                                        // (−1: no position criterion or no path)
  double max_winding_jump_turns = 0.0;  // largest winding change between resampled states
  double final_winding_turns = 0.0;     // winding about the report line at the end
  // Largest |entry| of the final writhe matrix of the report pair: row (robot chain segment),
  // col (object chain segment), value; −1, −1, 0 without a report pair or path.
  int writhe_peak_row = -1, writhe_peak_col = -1;
  double writhe_peak_value = 0.0;
  std::string failure_detail;  // PlanVerdict::detail: the joint or pair of the first violation
  // The report chain against the report object's closed loop at the end (PlanVerdict): checked
  // when the report object chain is closed; the chain segment that crosses the loop, or −1.
  bool loop_checked = false;
  bool passed_through = false;
  int through_segment = -1;
};

struct PlanResult {
  PlanReport report;
  Trajectory trajectory;  // AICO: T+1 slices; RRT: tree waypoints (empty on failure)
};

// The validity test of every planner and of every output-path check: q inside the joint limits
// and not InCollision (one counted query on `coll` per call). `s`, `coll` and `kin` must outlive
// the returned function.
ValidityFn ValidityChecker(const Scenario& s, CollisionData* coll, KinematicsData* kin);

// The sampling planners' problem: the joint-limit box (a continuous joint: one turn, ±π, around
// its start value), q_0 → the final-pose estimate goal_q.
RrtProblem ScenarioRrtProblem(const Scenario& s);

// Runs one planner on the scenario. AICO: RunAicoAttempts (its collision feature's queries and
// the validations at check_resolution are counted); RRT/BiRRT: PlanRrt / PlanBiRrt from q0 to
// goal_q with a validity checker (joint limits + InCollision, one counted query per state) inside
// the joint-limit box. `seed` seeds the RRTs' std::mt19937. OMPL planners: the same checker, box,
// goal, scenario.rrt options (range, resolution, goal_bias, max_checks) and seed, through OMPL (no
// path simplification). The AICO callback, if given, is forwarded. `poll`, if given, is called
// every few RRT/BiRRT iterations; it may throw to abort the run (the CLI's interrupt/--timeout
// check).
using PollFn = std::function<void()>;
PlanResult RunPlanner(const Scenario& scenario, Planner planner, unsigned seed,
                      const AicoCallback& callback = {}, const PollFn& poll = {});

// One run's request: what a caller may choose without changing the (immutable) scenario.
struct PlanRequest {
  Planner planner = Planner::kAico;
  unsigned seed = 0;
  // The world to plan in (objects moved, see MoveObject); null: scenario.initial.
  const ScenarioState* state = nullptr;
  // Replaces scenario.aico for this run (each attempt keeps its own iteration limit); the
  // viewer's planner panel edits these.
  std::optional<AicoOptions> aico;
  AicoCallback callback;
  PollFn poll;
};
// RunPlanner above, as the request says.
PlanResult RunPlanner(const Scenario& scenario, const PlanRequest& request);

// The result of a sampling planner's run `r` (RRT, BiRRT, the OMPL peers; `queries` and
// `narrow_phase_calls` counted while it ran), as RunPlanner reports it: the path re-checked at
// check_resolution on an uncounted collision state, then FinishReport. time_s is left 0. The
// viewer's stepped RRTs report through it too.
PlanResult SamplingPlanResult(const Scenario& scenario, const ScenarioState& state,
                              Planner planner, const RrtResult& r, long queries,
                              long narrow_phase_calls);

// The judged part of every run's report: start writhe, the verdict of JudgePlan on the path (when
// not `judged` already, as RunAicoAttempts does), path length, success = `found` (a path was
// found), path_collision_free and no failure reason; without a path, the end quantities of q0.
// Then NameFailure.
void FinishReport(const Scenario& scenario, const ScenarioState& state, bool found, bool judged,
                  PlanResult* out);

// AICO on the scenario, as RunPlanner runs it: attempt k (aico_attempts) is an AicoSolver on
// AttemptProblem(s, k) stepped one sweep at a time, `callback(sweep, cost, accepted, trajectory())`
// after each sweep (it may throw to cancel), then folded in by AddAicoAttempt; the next attempt
// runs only when one fails. With s.stop_when_solved, after every accepted sweep that does not end
// the solve, the trajectory is tested as a finished plan: the end conditions of its last slice
// (CheckEndState, no collision query), then the counted validation at check_resolution, then
// JudgePlan; the first success ends the run with status kSolved (its validation counted once), and
// every failed test's validation queries are added to collision_checks and narrow_phase_calls. A
// success first reached by the sweep that ends the solve is judged as without the option (status
// kConverged or kMaxIterations). Success can only be more frequent than without the option: a
// trajectory that passes part-way is returned even if the converged one would fail (and no retry
// attempt runs). Fills every report field of an AICO run except time_s and start_writhe_total; does
// not call NameFailure.
PlanResult RunAicoAttempts(const Scenario& scenario, const AicoCallback& callback = {});
// The same in the world `state` with `aico` instead of scenario.aico.
PlanResult RunAicoAttempts(const Scenario& scenario, const ScenarioState& state,
                           const AicoOptions& aico, const AicoCallback& callback = {});

// Folds one AICO solve `r` of the scenario (or of one of its attempts' problems) into `out`, as
// RunAicoAttempts does for every attempt: trajectory, status, cost and its history are replaced;
// iterations are added; collision checks (the solver's r.collision_queries plus the validation's)
// and narrow-phase calls (r.narrow_phase_calls plus the validation's) are added; the path is
// validated at check_resolution (counted queries) and judged by JudgePlan, whose fields fill the
// report (ApplyVerdict). Returns whether the attempt is a success (valid path, no failure reason);
// report.success is set accordingly.
bool AddAicoAttempt(const Scenario& s, const AicoResult& r, PlanResult* out);
bool AddAicoAttempt(const Scenario& s, const ScenarioState& state, const AicoResult& r,
                    PlanResult* out);

// Copies a verdict's fields into a report (final writhe, clearance, failure reason and step,
// reach error, winding jump and final winding, writhe peak).
void ApplyVerdict(const PlanVerdict& v, PlanReport* report);

// Names a failed run (report.success false) by its solver status when that status is a failure
// in itself: kDiverged, kInvalidInput, kBudgetExhausted replace the verdict's reason; after
// kConverged / kMaxIterations a run without a verdict reason is kBudgetExhausted (no path within
// the limits; kSolved only ends successful runs). A successful report is left as it is.
void NameFailure(PlanReport* report);

}  // namespace planning
