// Running a planner on a set-up scenario: one runner shared by the `plan` and `bench` commands,
// the tests and the benchmarks; the success criteria and the report metrics.
#pragma once

#include <string>
#include <vector>

#include "planning/aico.h"
#include "planning/scenario.h"
#include "planning/trajectory.h"

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
};

struct PlanResult {
  PlanReport report;
  Trajectory trajectory;  // AICO: T+1 slices; RRT: tree waypoints (empty on failure)
};

// Runs one planner on the scenario. AICO: SolveAico on each attempt's problem (its collision
// feature's queries are counted) plus the validation of the result at check_resolution, the next
// attempt only when one fails; RRT/BiRRT: PlanRrt / PlanBiRrt from q0 to goal_q with a validity
// checker (joint limits + InCollision, one counted query per state) inside the joint-limit box.
// `seed` seeds the RRTs' std::mt19937. OMPL planners: the same checker, box, goal, scenario.rrt
// options (range, resolution, goal_bias, max_checks) and seed, through OMPL (no path
// simplification). The AICO callback, if given, is forwarded.
PlanResult RunPlanner(const Scenario& scenario, Planner planner, unsigned seed,
                      const AicoCallback& callback = {});

// The scenario's success criteria at a final configuration q with report-pair writhe
// `final_writhe` (SuccessCriteria, scenario.h).
bool MeetsSuccessCriteria(const Scenario& scenario, const Eigen::VectorXd& q, double final_writhe);

}  // namespace planning
