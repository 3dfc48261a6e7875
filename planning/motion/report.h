// The files a planning run is reported in: report.json, trajectory.csv, a summary line, and the
// rows of the Fig. 4.5 benchmark. Plain data out of PlanReport / UnwrapBenchmarkResult, shared by
// the command line, the demo, the viewer and the Python module.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "planning/motion/planner.h"
#include "planning/motion/unwrap_benchmark.h"

namespace planning {

// report.json of `topoplan plan`: scenario, planner, seed, success, status, collision_checks,
// narrow_phase_calls, state_queries, bool/distance_pair_tests, cpu_time_s, goal_sampler_draws,
// goal_samples, goal_sampler_{state_queries, bool_pair_tests, distance_pair_tests, cpu_time_s},
// iterations, attempts, cost, path_length [rad], time_s, start_wrap_deg,
// start/final_writhe_total, min_clearance_m, path_collision_free, cost_history, failure_reason
// (FailureReasonName), failure_step, reach_error_m, max_winding_jump_turns, winding_jumps
// {through_object, beyond_ends, unlocated}, final_winding_turns, and writhe_peak {row, col, value}
// (largest |entry| of the final writhe matrix of the report pair; only with a report pair).
nlohmann::json PlanReportJson(const Scenario& scenario, const PlanReport& report, unsigned seed);

// trajectory.csv: "step,time_s,<joint names in robot order>", one row per slice, 17 digits.
std::string TrajectoryCsv(const Scenario& scenario, const Trajectory& trajectory);

// One human-readable line: planner, scenario, start wrap, success/status, checks, iterations,
// time, writhe start -> final, min clearance (no trailing newline).
std::string PlanSummaryLine(const Scenario& scenario, const PlanReport& report);

// unwrap.csv: "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,
// time_s,path_length,reach_error_m,pole_offset_m,state_queries,bool_pair_tests,
// distance_pair_tests,cpu_time_s,setup_time_s,goal_samples,goal_sampler_state_queries,
// goal_sampler_pair_tests,goal_sampler_cpu_time_s", one row per run in result.runs order (the
// goal_sampler columns: the goal-region planners' sampler share, PlanReport; 0 for the others).
std::string UnwrapCsv(const UnwrapBenchmarkResult& result);

}  // namespace planning
