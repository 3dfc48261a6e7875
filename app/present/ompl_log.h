// `bench unwrap --ompl-log FILE`: the benchmark in the text log format of OMPL's
// ompl::tools::Benchmark (saveResultsToFile), which OMPL's ompl_benchmark_statistics.py reads into
// the SQLite database that Planner Arena plots.
//
// That script reads exactly one experiment per log file, so the sweep becomes one experiment per
// angle to unwrap, each in its own file (OmplLogPath). In each experiment every topoplan planner is
// one OMPL "planner" and every seed one run with the properties (name, SQL type, value):
//   bool pair tests INTEGER     PlanReport::counts.bool_pair_tests
//   collision checks INTEGER    PlanReport::collision_checks
//   cpu time REAL               PlanReport::cpu_time_s [s, process CPU time of the solve]
//   distance pair tests INTEGER PlanReport::counts.distance_pair_tests
//   failure reason ENUM         planning::FailureReason as an integer (the log's one enum type,
//                               "failure_reason", lists the names in enum order)
//   iterations INTEGER          PlanReport::iterations
//   narrow phase calls INTEGER  PlanReport::narrow_phase_calls
//   path length REAL            PlanReport::path_length [rad, joint space]
//   pole offset REAL            |UnwrapRun::pole_offset| [m]
//   reach error REAL            PlanReport::reach_error_m [m]
//   seed INTEGER                UnwrapRun::seed
//   setup time REAL             PlanReport::setup_time_s [s, wall time of the scenario set-up]
//   solved BOOLEAN              PlanReport::success (1/0)
//   state queries INTEGER       PlanReport::counts.state_queries
//   time REAL                   PlanReport::time_s [s, wall clock]
// (sorted by name, as OMPL writes them). Non-finite numbers are written "nan", which the script
// stores as NULL.
#pragma once

#include <string>

#include "planning/motion/unwrap_benchmark.h"

namespace app {

// What the log header says about the run (the results themselves come from the result struct).
struct OmplLogInfo {
  std::string library = "topoplan";  // first header line: "<library> version <version>"
  std::string version;
  std::string host = "UNKNOWN";  // "Running on <host>" (one word)
  std::string start_time;        // "Starting at <start_time>", e.g. 2026-12-01T00:40:00
  std::string setup;             // free text between <<<| and |>>> (no line may start with |>>>)
  long rrt_budget = -1;          // RRT collision-check budget (<= 0: the scenario's own)
  std::string budget;            // --budget as given (planner.h BudgetText; "" none)
  double perturb_m = 0.0;        // pole perturbation [m]
};

// The log of angle index `angle` of `result` (< result.angles_deg.size()): experiment
// "unwrap_<angle>deg" with experiment properties angle_deg, seeds, perturb_m; one planner block
// per result.planners entry (its runs in seed order); run count = result.seeds. Throws
// std::invalid_argument for an angle index out of range or runs that do not match the result's
// angles × planners × seeds layout.
std::string OmplBenchmarkLog(const planning::UnwrapBenchmarkResult& result, size_t angle,
                             const OmplLogInfo& info);

// FILE with "_<angle>deg" before its extension: ("out/unwrap.log", 720) -> "out/unwrap_720deg.log",
// ("log", 22.5) -> "log_22.5deg".
std::string OmplLogPath(const std::string& file, double angle_deg);

}  // namespace app
