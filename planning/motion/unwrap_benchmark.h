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

namespace planning {

// One benchmark run: `planner` with `seed` on the scenario loaded with start wrap `angle_deg`.
struct UnwrapRun {
  double angle_deg = 0.0;  // angle to unwrap (scenario start wrap) [deg]
  Planner planner = Planner::kAico;
  int seed = 0;  // seed of the RRTs' generator and of the pole offset (AICO is deterministic)
  Eigen::Vector3d pole_offset = Eigen::Vector3d::Zero();  // world-frame pole offset [m]
  PlanReport report;  // success, status, collision_checks (configuration-level queries),
                      // narrow_phase_calls, iterations, time_s (wall clock, the only
                      // non-deterministic field), path_length [rad], final_writhe_total, ...
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
  // Pole perturbation [m], >= 0: each seed s moves the writhe-report object (the pole) by
  // UnwrapPoleOffset(s, perturb_m, axis) before the scenario is set up (0: the shipped placement).
  double perturb_m = 0.0;
  // Replaces the scenario's aico.stop_when_solved when set (planner.h RunAicoAttempts).
  std::optional<bool> aico_stop_when_solved;
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
// RunPlanner (with perturb_m > 0: the pole of seed s moved by UnwrapPoleOffset about the report
// line of the unperturbed scenario). Throws std::invalid_argument for bad options (no
// angles/planners, seeds < 1, perturb_m negative or not finite) and
// whatever LoadScenario throws for a bad scenario file.
UnwrapBenchmarkResult RunUnwrapBenchmark(const UnwrapBenchmarkOptions& options);

// The summary of `runs` (ordered as in UnwrapBenchmarkResult::runs) for the given angles and
// planners: one cell per (angle, planner), angle-major, planners in the given order.
std::vector<UnwrapCell> SummarizeUnwrapRuns(const std::vector<UnwrapRun>& runs,
                                            const std::vector<double>& angles_deg,
                                            const std::vector<Planner>& planners);

// summary cell of angle index `a` and planner index `p`.
const UnwrapCell& UnwrapSummaryCell(const UnwrapBenchmarkResult& result, size_t a, size_t p);

}  // namespace planning
