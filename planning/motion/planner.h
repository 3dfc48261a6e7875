// Running a planner on a set-up scenario: one runner shared by the `plan` and `bench` commands,
// the tests and the benchmarks; the success criteria and the report metrics.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/motion/aico.h"
#include "planning/motion/rrt.h"
#include "planning/motion/scenario.h"
#include "planning/motion/success.h"
#include "planning/motion/trajectory.h"
#include "planning/robot/kinematics.h"

namespace planning {

// kOmplRrt / kOmplRrtConnect: OMPL's geometric RRT (goal bias from the scenario, 0.1) and
// RRTConnect as a peer check of the project's RRTs, on the same checker, counter, budget, goal and
// edge resolution (only when built with OMPL, see OmplAvailable).
// kAicoGoal ("aico-goal"): AICO on the same problem without its writhe terms (every task whose
// feature is a writhe matrix or total, WritheTaskNames), the baseline that has the reach,
// collision and guard terms but no topology target (docs/results/unwrap.md).
// kRrtRegion / kBiRrtRegion ("rrt-region", "birrt-region"): RRT and BiRRT whose goal is the region
// of every configuration meeting the success criterion's end conditions (goal_region.h,
// scenario_goal_region.h), sampled lazily by projection and rejection, instead of q̂_T; the same
// start, checker, box, edge resolution, options and budget as kRrt / kBiRrt.
// kOmplRrtRegion / kOmplRrtConnectRegion ("ompl-rrt-region", "ompl-rrtconnect-region"): their OMPL
// peers, OMPL's RRT and RRTConnect with the same region as an ob::GoalSampleableRegion
// (internal/ompl_planners.h PlanOmplRegion; only when built with OMPL).
enum class Planner {
  kAico,
  kRrt,
  kBiRrt,
  kOmplRrt,
  kOmplRrtConnect,
  kAicoGoal,
  kRrtRegion,
  kBiRrtRegion,
  kOmplRrtRegion,
  kOmplRrtConnectRegion
};
// kAico or kAicoGoal.
bool IsAico(Planner planner);

// The registry: every planner of this build, in order ("aico", "rrt", "birrt", "ompl-rrt",
// "ompl-rrtconnect" when built with OMPL, "aico-goal", "rrt-region", "birrt-region",
// "ompl-rrt-region", "ompl-rrtconnect-region" when built with OMPL).
std::vector<Planner> AvailablePlanners();
// The planners a sweep runs when none are named (`bench unwrap`, the demo): AvailablePlanners()
// without the OMPL goal-region peers, which check rrt-region / birrt-region and are run by name.
std::vector<Planner> DefaultPlanners();
// "aico" | "rrt" | "birrt" | "ompl-rrt" | "ompl-rrtconnect" | "aico-goal" | "rrt-region" |
// "birrt-region" | "ompl-rrt-region" | "ompl-rrtconnect-region"; throws std::invalid_argument for
// an unknown name (listing the valid ones), and for the OMPL names when built without OMPL
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
  // The common cost units (collision.h QueryCounts), counted the same way for every planner:
  // AICO's feature evaluations (collision, line clearance, winding guard; rollout included) plus
  // its validations at check_resolution; a sampling planner's validity checks. Deterministic.
  QueryCounts counts;
  double cpu_time_s = 0.0;    // process CPU time of the solve [s] (not deterministic)
  double setup_time_s = 0.0;  // wall time of the scenario set-up before the solve [s] (callers
                              // that set the scenario up fill it; RunPlanner leaves it 0)
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
  WindingJumps winding_jumps;           // the winding jumps by place (success.h)
  double final_winding_turns = 0.0;     // winding about the report line at the end
  // Largest |entry| of the final writhe matrix of the report pair: row (robot chain segment; with
  // success.writhe_closure "chord" the last row is the chord's), col (object chain segment),
  // value; −1, −1, 0 without a report pair or path.
  int writhe_peak_row = -1, writhe_peak_col = -1;
  double writhe_peak_value = 0.0;
  std::string failure_detail;  // PlanVerdict::detail: the joint or pair of the first violation
  // The report chain against the report object's closed loop at the end (PlanVerdict): checked
  // when the report object chain is closed; the chain segment that crosses the loop, or −1.
  bool loop_checked = false;
  bool passed_through = false;
  int through_segment = -1;
  // Goal-region planners: the goal sampler's share of the totals above (scenario_goal_region.h):
  // draws made, goal states found (valid candidates in the region), the state queries and pair
  // tests of its validity checks (part of `counts`) and the CPU time of its draws and checks (part
  // of cpu_time_s). All 0 for the other planners.
  long goal_sampler_draws = 0;
  long goal_samples = 0;
  QueryCounts goal_sampler_counts;
  double goal_sampler_cpu_time_s = 0.0;
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
// the joint-limit box; rrt-region / birrt-region: a GoalRegionSolver from q0 to
// ScenarioGoalRegion with the same checker (the sampler's checks counted in the same budget).
// `seed` seeds the RRTs' std::mt19937. OMPL planners: the same checker, box, goal, scenario.rrt
// options (range, resolution, goal_bias, max_checks) and seed, through OMPL (no path
// simplification). The AICO callback, if given, is forwarded. `poll`, if given, is called every few
// RRT/BiRRT iterations; it may throw to abort the run (the CLI's interrupt/--timeout check).
using PollFn = std::function<void()>;

// A run's budget in one cost unit: the run ends with status kBudgetExhausted once it has spent it.
// kQueries: state queries (QueryCounts::state_queries; the RRTs' max_checks, exact); kCpuTime:
// process CPU seconds of the solve; kPairTests: pair tests of both kinds (QueryCounts::pair_tests).
// AICO tests it after every sweep, RRT/BiRRT after every iteration, OMPL at every poll of its
// termination condition, so a run may overshoot by one sweep or iteration, and is then no success
// (EnforceBudget); whether a run solved within budget b is read off its counts (SolvedWithin).
struct Budget {
  enum class Unit { kNone, kQueries, kCpuTime, kPairTests };
  Unit unit = Unit::kNone;  // kNone: the scenario's own limits
  double value = 0.0;       // state queries, CPU seconds or pair tests
};
// "queries=N" | "pairs=N" (N a positive integer) | "time=S" (S > 0 seconds, CPU) | "N" (=
// queries=N). Throws std::invalid_argument naming `flag` for anything else.
Budget ParseBudget(const std::string& text, const std::string& flag);
// "queries=100000" / "pairs=100000" / "time=2.5" (ParseBudget's syntax); "" for kNone.
std::string BudgetText(const Budget& budget);
// Whether `report` is a success that spent at most `budget` (its counts or cpu_time_s); every
// success for kNone.
bool SolvedWithin(const PlanReport& report, const Budget& budget);
// A budget is a limit: a success that spent more than `budget` (a run tests a polled budget after
// a sweep or an iteration, and may cross it there) becomes a failure with status and reason
// kBudgetExhausted. RunPlanner applies it to every run.
void EnforceBudget(const Budget& budget, PlanReport* report);
// Process CPU time [s] (CLOCK_PROCESS_CPUTIME_ID).
double CpuSeconds();
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
  Budget budget;  // kNone: the scenario's limits (rrt.max_checks, aico iterations)
  // AICO only: task terms switched off (ablations): the tasks of these names get precision 0 and
  // max_jump 0 in every attempt's problem (the features stay, for the success judge). Unknown
  // names throw std::invalid_argument.
  std::vector<std::string> disabled_tasks;
  bool aico_retry = true;  // AICO only: false runs attempt 0 alone (the no-retry ablation)
};
// RunPlanner above, as the request says.
PlanResult RunPlanner(const Scenario& scenario, const PlanRequest& request);

// The result of a sampling planner's run `r` (RRT, BiRRT, the OMPL peers; `coll` the collision
// state its checker used: queries, narrow-phase calls and QueryCounts), as RunPlanner reports it:
// the path re-checked at check_resolution on an uncounted collision state, then FinishReport.
// time_s is left 0. The viewer's stepped RRTs report through it too.
PlanResult SamplingPlanResult(const Scenario& scenario, const ScenarioState& state, Planner planner,
                              const RrtResult& r, const CollisionData& coll);

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
// attempt runs). An attempt whose init is not AicoInit::kDefault (aico.retry's "init") starts
// from internal::UnwindingInit at the state's q0 in the state's world, built for the attempt's
// problem (tasks switched off are left out of it), and the continuations' state queries, pair
// tests, collision queries and FCL calls are counted in the report (when they spend the budget,
// the attempt does not start and the run fails as kBudgetExhausted; `attempts` counts the attempts
// started). The plain unwinding path (kUnwinding) depends on q0 alone: it is made and charged
// once, and a later attempt from it reuses it. Fills every report field of an AICO run except
// time_s and start_writhe_total; does not call NameFailure.
PlanResult RunAicoAttempts(const Scenario& scenario, const AicoCallback& callback = {});
// The same in the world `state` with `aico` instead of scenario.aico.
// With a budget (not kNone): after every sweep the counts (or CPU time) spent so far, earlier
// attempts included, are compared with it; once spent after a sweep that was no success (with
// stop_when_solved), the run ends as a failure: status and failure reason kBudgetExhausted.
// `retry` false: attempt 0 only. An unwinding-init attempt (any init but kDefault) is skipped when
// `disabled_tasks` holds a writhe task (the continuations follow the arm's topology about the pole,
// its writhe or its winding: aico-goal and the no-writhe ablation do not get them).
PlanResult RunAicoAttempts(const Scenario& scenario, const ScenarioState& state,
                           const AicoOptions& aico, const AicoCallback& callback = {},
                           const Budget& budget = {},
                           const std::vector<std::string>& disabled_tasks = {}, bool retry = true);

// `problem` (one task per scenario task) with the tasks named in `names` switched off (precision
// 0, max_jump 0). Throws std::invalid_argument for a name that is no task of the scenario.
void DisableTasks(const std::vector<std::string>& names, MotionProblem* problem);
// The names of the tasks of `problem` whose feature is a writhe (what aico-goal switches off).
std::vector<std::string> WritheTaskNames(const MotionProblem& problem);

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
