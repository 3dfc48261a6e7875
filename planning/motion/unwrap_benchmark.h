// The thesis Fig. 4.5 experiment as a library call: collision checks needed to unwrap an arm coiled
// around a pole, per start angle, planner and seed, plus the per-(angle, planner) summary the
// figure and the tables show.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "planning/motion/planner.h"
#include "planning/motion/unwrap_geometry.h"

namespace planning {

// One benchmark run: `planner` with `seed` on the scenario loaded with start wrap `angle_deg`.
struct UnwrapRun {
  double angle_deg = 0.0;  // angle to unwrap (scenario start wrap) [deg]
  Planner planner = Planner::kAico;
  int seed = 0;  // seed of the RRTs' generator and of the pole offset (AICO is deterministic)
  Eigen::Vector3d pole_offset = Eigen::Vector3d::Zero();  // world-frame pole offset [m]
  PlanReport report;    // success, status, counts (state queries, pair tests), collision_checks,
                        // narrow_phase_calls, iterations, time_s / cpu_time_s / setup_time_s (the
                        // non-deterministic fields), path_length [rad], final_writhe_total, ...
  std::string variant;  // ablation runs: the UnwrapAblation's name; "" otherwise
  // The set-up's goal q̂_T (the RRTs' goal, searched to meet the end conditions) meets every end
  // condition of the success criterion (success.h CheckEndState with state checks): false means
  // no configuration the set-up found ends as a success must, on this scenario and geometry.
  bool goal_meets_end_conditions = false;
  // Winding (turns) about the report line of the straight segment from the report chain's first
  // point (the arm's base, fixed) to the reach target: about the winding an arm that does not wrap
  // the pole ends with (its chain ends near the target), the reference for the criterion's
  // |final winding| < final_below. 0 without a report pair or position criterion.
  double unwound_winding_turns = 0.0;
  // 360°·|writhe| at the start of the report chain closed by its chord (the segment from its last
  // point back to its first) with the report object's chain [deg]: the loops the start coil makes
  // round the pole's axis (about an infinite line, a whole number of turns: the linking number;
  // about the finite pole's axis off by a fraction of a turn). start_wrap_deg, the open chain's,
  // also counts the chord's part, which depends on where the hand is. 0 without a report pair.
  double start_closed_wrap_deg = 0.0;
  // The set-up's warnings for this run's angle and seed (Scenario::warnings: a start coil that
  // collides, leaves the joint limits or is not clear of the pole's line).
  std::vector<std::string> setup_warnings;
};

// Aggregate of the runs of one (angle, planner) pair.
struct UnwrapCell {
  double angle_deg = 0.0;  // [deg]
  Planner planner = Planner::kAico;
  int runs = 0;       // seeds run
  int successes = 0;  // runs with report.success
  // Mean and median of collision_checks over the SUCCESSFUL runs (NaN when none succeeded);
  // failed runs stop at the budget and are reported separately, as in the figure.
  double mean_checks = 0.0;
  double median_checks = 0.0;
};

struct UnwrapBenchmarkOptions {
  std::string scenario_path;       // the unwrap scenario JSON (coil start, "start_wrap_deg")
  std::vector<double> angles_deg;  // start wraps to run [deg], in output order
  std::vector<Planner> planners;   // in output order (kept everywhere, never re-sorted)
  int seeds = 3;                   // seeds 0..seeds-1 per angle and planner
  long rrt_budget = -1;            // RRT collision-check budget; <= 0: the scenario's own
  // Every planner's budget (planner.h Budget; kNone: the scenario's limits). A queries budget also
  // replaces the RRTs' max_checks.
  Budget budget;
  // Pole perturbation [m], >= 0: each seed s moves the writhe-report object (the pole) by
  // UnwrapPoleOffset(s, perturb_m, axis) before the scenario is set up (0: the shipped placement).
  double perturb_m = 0.0;
  // Replaces the scenario's aico.stop_when_solved when set (planner.h RunAicoAttempts).
  std::optional<bool> aico_stop_when_solved;
  // The geometry to run on (unwrap_geometry.h ApplyUnwrapGeometry, applied to the parsed scenario
  // before the pole perturbation); unset: the scenario as shipped.
  std::optional<UnwrapGeometry> geometry;
  // Where relative robot/object paths of the scenario are also looked up (see ScenarioOverrides).
  std::vector<std::string> search_roots;
  // Called after every run with the number of runs done so far and the total.
  std::function<void(int done, int total, const UnwrapRun& run)> progress;
};

struct UnwrapBenchmarkResult {
  std::vector<double> angles_deg;  // as given
  std::vector<Planner> planners;   // as given
  int seeds = 0;
  // Angle-major, then planner (given order), then seed: runs[(a * P + p) * seeds + s].
  std::vector<UnwrapRun> runs;
  // Angle-major, then planner: summary[a * P + p] (see UnwrapSummaryCell).
  std::vector<UnwrapCell> summary;
};

// The pole offset of seed `seed`: uniform in the disc of radius `max_m` perpendicular to
// `axis_direction` (non-zero), drawn from std::mt19937(seed) with the portable mapping of
// planning/random.h (u1, u2 = UniformUnit; r = max_m·√u1, φ = 2π·u2; r(cos φ e1 + sin φ e2), with
// e1 = normalize(d × x̂) (d × ŷ when |d_x| >= 0.9), e2 = d × e1), so a seed gives the same offset
// with every standard library. max_m = 0: zero.
Eigen::Vector3d UnwrapPoleOffset(int seed, double max_m, const Eigen::Vector3d& axis_direction);

// The pole perturbation of a benchmark: the object that moves (the scenario's writhe-report
// object) and the offset of each seed (UnwrapPoleOffset about the report line of the unperturbed
// scenario). perturb_m = 0: object -1 and zero offsets.
struct UnwrapPerturbation {
  int object = -1;                       // index into ScenarioSpec::objects; -1: nothing moves
  std::string object_name;               // its name ("" when object is -1)
  std::vector<Eigen::Vector3d> offsets;  // world-frame offset of seed s [m], size = seeds
};
// Sets `spec` up once (at angle_deg; the report line does not depend on the start wrap) to find
// the pole's line. Throws std::invalid_argument for seeds < 1, perturb_m negative or not finite,
// and perturb_m > 0 without a writhe_report in the scenario.
UnwrapPerturbation MakeUnwrapPerturbation(const ScenarioSpec& spec, double angle_deg, int seeds,
                                          double perturb_m);
// `spec` with perturbation.object moved by offsets[seed] (unchanged when object is -1).
ScenarioSpec PerturbedUnwrapSpec(ScenarioSpec spec, const UnwrapPerturbation& perturbation,
                                 int seed);

// Runs every (angle, planner, seed) with LoadScenario(scenario_path, {start_wrap_deg = angle}) and
// RunPlanner (with options.budget; report.setup_time_s = the wall time of the scenario's set-up,
// which the runs on one set-up share) (with perturb_m > 0: the pole of seed s moved by
// UnwrapPoleOffset about the report line of the unperturbed scenario). Throws std::invalid_argument
// for bad options (no angles/planners, seeds < 1, perturb_m negative or not finite) and whatever
// LoadScenario throws for a bad scenario file.
UnwrapBenchmarkResult RunUnwrapBenchmark(const UnwrapBenchmarkOptions& options);

// The summary of `runs` (ordered as in UnwrapBenchmarkResult::runs) for the given angles and
// planners: one cell per (angle, planner), angle-major, planners in the given order.
std::vector<UnwrapCell> SummarizeUnwrapRuns(const std::vector<UnwrapRun>& runs,
                                            const std::vector<double>& angles_deg,
                                            const std::vector<Planner>& planners);

// summary cell of angle index `a` and planner index `p`.
const UnwrapCell& UnwrapSummaryCell(const UnwrapBenchmarkResult& result, size_t a, size_t p);

// --- Budget-free verdicts: survival over a budget sweep -----------------------------------------

// Fraction of the runs of one (planner, angle) solved within one budget (SolvedWithin), the
// cumulative time-to-solve curve of Planner Arena (Moll, Sucan, Kavraki 2015). A budget only
// truncates a run (RRT/BiRRT/OMPL stop at it, AICO after the sweep that reaches it, and a success
// that sweep reaches past the budget is a budget failure: RunPlanner), so one run at the largest
// budget gives the verdict at every smaller one.
struct UnwrapSurvivalPoint {
  Planner planner = Planner::kAico;
  double angle_deg = 0.0;
  Budget budget;  // unit and value of this point
  int runs = 0;
  int solved = 0;  // runs that succeeded within the budget
  // Failures of the sweep's runs (at the largest budget): stopped by the budget (status or reason
  // kBudgetExhausted: more budget may solve them) or another failure (converged to a failed
  // trajectory, diverged, invalid: no budget solves them).
  int failed_budget = 0;
  int failed_other = 0;
};

// The budgets of a sweep: `points` values log-spaced from `lo` to `hi` (> lo > 0), both included.
std::vector<double> LogBudgets(double lo, double hi, int points);

// The survival points of `result` for each planner, angle and budget value of `unit` (kQueries:
// state queries; kPairTests: pair tests of both kinds; kCpuTime: cpu_time_s), planner-major, then
// angle, then budget.
std::vector<UnwrapSurvivalPoint> UnwrapSurvival(const UnwrapBenchmarkResult& result,
                                                Budget::Unit unit,
                                                const std::vector<double>& budgets);

// "unit,budget,planner,angle_deg,runs,solved,fraction,failed_budget,failed_other" rows; unit is
// state_queries, pair_tests or cpu_time_s.
std::string UnwrapSurvivalCsv(const std::vector<UnwrapSurvivalPoint>& points);

// --- Ablations ----------------------------------------------------------------------------------

// One AICO variant: the full problem ("full") or one task term removed.
struct UnwrapAblation {
  std::string name;                         // "full", "no-writhe", "no-reach", ...
  std::vector<std::string> disabled_tasks;  // PlanRequest::disabled_tasks
  bool no_rollout = false;                  // aico.rollout_init off (q0 repeated)
  bool no_retry = false;                    // attempt 0 only (PlanRequest::aico_retry false)
};

// "full", then each task term of the scenario removed in turn: "no-writhe" (tasks with a writhe
// feature), "no-reach" (the success criterion's position task), "no-off-pole" (line-clearance
// tasks), "no-winding-guard" (tasks with max_jump > 0), "no-rollout" (when aico.rollout_init is
// on), "no-retry" (when aico.retry is given). A term the scenario does not have is left out.
std::vector<UnwrapAblation> UnwrapAblations(const ScenarioSpec& spec);

// Every (angle, ablation, seed) of AICO, as RunUnwrapBenchmark (same scenario, perturbation,
// budget, stop rule): runs in angle, ablation, seed order, UnwrapRun::variant = the ablation's
// name, planner kAico. `ablations` receives the variants run (in order). Throws as
// RunUnwrapBenchmark.
UnwrapBenchmarkResult RunUnwrapAblation(const UnwrapBenchmarkOptions& options,
                                        std::vector<UnwrapAblation>* ablations);

// "angle_deg,ablation,seed,success,failure_reason,final_writhe_total,reach_error_m,
// final_winding_turns,state_queries,cpu_time_s" rows of an ablation result.
std::string UnwrapAblationCsv(const UnwrapBenchmarkResult& result);

// "geometry,split,angle_deg,planner,seed,start_wrap_deg,start_closed_wrap_deg,success,
// failure_reason,final_writhe_total,reach_error_m,final_winding_turns,unwound_winding_turns,
// goal_meets_end_conditions,state_queries,cpu_time_s,setup_time_s,jumps_through_object,
// jumps_beyond_ends,jumps_unlocated" rows of a benchmark run on `geometry` (bench unwrap
// --geometry; the jumps: PlanReport's, by where the arm passes the pole's line): start_wrap_deg =
// 360°·|start writhe| is the coil the start continuation reached (it can fall short of angle_deg on
// a geometry where the arm cannot coil that far), start_closed_wrap_deg the UnwrapRun's,
// reach_error_m in m, final_winding_turns in turns; planner is the UnwrapRun's variant for an
// ablation run.
std::string UnwrapGeometryCsv(const UnwrapGeometry& geometry, const UnwrapBenchmarkResult& result);

}  // namespace planning
