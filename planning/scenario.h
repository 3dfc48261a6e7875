// Planning scenarios (assets/scenarios/*.json): the one loader, and one runner shared by the
// `plan` and `bench` commands, the tests and the benchmarks.
//
// File format (paths are relative to the scenario file; angles in radians, lengths in metres):
// {
//   "name": "unwrap",
//   "robot": "../robots/arm20_sdh.urdf",
//   "objects": [{"name": "pole", "urdf": "../objects/pole.urdf", "xyz": [x,y,z], "rpy": [r,p,y],
//                "collide": true, "capsules": {"chain": "loop", "radius": 0.012}}, ...],
//     ("capsules": collide with capsules along that chain of the object instead of its own
//      geometry; "collide": false: chains and rendering only),
//   "robot_chains": [{"name": "hand", "points": [{"link": "l", "xyz": [0, 0, 0]}, ...]}],
//     (extra chains on the robot, appended to the URDF's chains)
//   "collision": {"self": true, "disabled_pairs": [["link_a", "link_b"], ...],
//                 "disabled_groups": [["sdh_", "arm_link_20"], ...]},  (link-name prefixes: no
//                 self-collision checks between any two links of a group)
//   "writhe_report": {"chain": "arm", "object": "pole", "object_chain": "axis"},
//   "start": {"q": [...]} | {"q": "zero"} |
//            {"coil": {"wrap_deg": 720, "step": 0.05}}   (start coil, see below),
//   "problem": {"T": 50, "duration": 2.0, "dynamic": true, "h_rate": 1, "w_rate": 1},
//   "tasks": [{"name": "...", "feature": {"type": ..., ...}, "order": 0,
//              "target": {"type": "zero" | "value" | "interpolate" | "final_pose", "value": [...]},
//              "precision": ρ_mid, "final_precision": ρ_T}, ...],
//   "final_pose": {"tasks": ["reach", ...], "alpha": 0.05, "init": "start" | "unwrapped"},
//   "success": {"writhe_total_below": 0.05, "position": {"task": "reach", "tolerance": 0.05},
//               "inside_box": "box"},
//   "aico": {"max_iterations": 40, "tolerance": 0.01, "damping": 1, "sweep_mode": "forwardly",
//            "max_step": 0.3, "rollout_init": true, "rollout_prior": 100,
//            "retry": {"precision_scale": {"qdot": 30, ...}, "max_iterations": 60}},
//   "rrt": {"range": 0.5, "resolution": 0.02, "goal_bias": 0.1, "max_checks": 100000}
// }
// Feature types: position {link, offset}, axis_alignment {link, axis, direction}, joint_limits
// {margin}, joint_position {}, box {link, offset, center, half_extent, margin}, writhe {chain,
// object, object_chain, output: "matrix"|"total"}, winding {chain, axis_point, axis_direction},
// collision {margin}. Target "interpolate" goes linearly from y(q_0) to "value"; "final_pose"
// from y(q_0) to y(q̂_T) (q̂_T = the final-pose estimate of thesis §4.2.2 over the listed tasks,
// which is also the RRT goal). Errors (unknown keys' values, wrong sizes, unknown links/objects,
// unreadable files) throw std::invalid_argument naming the file and the JSON path.
//
// Start coil: the start configuration is found by writhe continuation from q = 0 of the robot
// (the 20-link arm's zero pose is a coil around the pole): small damped Gauss–Newton steps that
// move the total writhe of writhe_report by `step` at a time under the collision and joint-limit
// tasks, until 360°·|writhe| = wrap_deg. Continuing to writhe 0 gives the "unwrapped" pose used to
// initialise the final-pose estimate. Deterministic.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "planning/aico.h"
#include "planning/collision.h"
#include "planning/final_pose.h"
#include "planning/robot.h"
#include "planning/rrt.h"
#include "planning/task.h"

namespace planning {

struct ScenarioOverrides {
  std::optional<double> start_wrap_deg;  // replaces start.coil.wrap_deg
};

struct SuccessCriteria {
  double writhe_total_below = -1.0;  // < 0: not checked
  int position_task = -1;            // index into problem.tasks; −1: not checked
  double position_tolerance = 0.05;
  int box_task = -1;  // index of a "box" task whose y must be 0 at the end
};

// A loaded scenario. Not movable (the problem and features point into it); use unique_ptr.
struct Scenario {
  Scenario() = default;
  Scenario(const Scenario&) = delete;
  Scenario& operator=(const Scenario&) = delete;

  std::string name;
  std::string source;  // scenario file
  Robot robot;
  Environment objects;  // every object (chains, rendering)
  Environment env;      // what the robot collides with (objects, or capsules replacing them)
  CollisionOptions collision;
  MotionProblem problem;  // q0, tasks (targets resolved), T, dt, process parameters
  AicoOptions aico;
  // Optional second AICO attempt (scenario "aico.retry"): the same tasks with per-task precision
  // multipliers, used only when the first attempt fails validation or the success criteria.
  bool has_retry = false;
  MotionProblem retry_problem;
  AicoOptions retry_aico;
  RrtOptions rrt;
  double check_resolution = 0.02;  // edge resolution for validating any output path
  Eigen::VectorXd goal_q;          // q̂_T (final-pose estimate): the RRT goal
  double start_wrap_deg = 0.0;     // 360°·|writhe| of the report pair at q0
  // Writhe report pair: robot chain × object chain (for report fields and heatmaps).
  int report_chain = -1;
  Eigen::Matrix3Xd report_object_chain;
  SuccessCriteria success;
};

// Loads and resolves a scenario (runs the start-coil continuation and the final-pose estimate).
std::unique_ptr<Scenario> LoadScenario(const std::string& path,
                                       const ScenarioOverrides& overrides = {});

// kOmplRrt / kOmplRrtConnect: OMPL's geometric RRT (goal bias from the scenario, 0.1) and
// RRTConnect as a peer check of the project's RRTs, on the same checker, counter, budget, goal and
// edge resolution (only when built with OMPL, see OmplAvailable).
enum class Planner { kAico, kRrt, kBiRrt, kOmplRrt, kOmplRrtConnect };
// "aico" | "rrt" | "birrt" | "ompl-rrt" | "ompl-rrtconnect"; throws std::invalid_argument for an
// unknown name, and for the OMPL names when built without OMPL ("... built without OMPL ...").
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
  int attempts = 1;             // AICO: 2 when the scenario's retry ran
  double cost = 0.0;            // AICO: final total cost; RRT: joint-space path length
  double path_length = 0.0;     // joint-space path length (rad)
  double time_s = 0.0;          // wall-clock planning time (the only non-deterministic field)
  double start_writhe_total = 0.0;
  double final_writhe_total = 0.0;
  double min_clearance_m = 0.0;  // minimum signed distance along the path at check_resolution
  bool path_collision_free = false;
  std::vector<double> cost_history;  // AICO accepted-sweep costs
};

struct PlanResult {
  PlanReport report;
  Trajectory trajectory;  // AICO: T+1 slices; RRT: tree waypoints (empty on failure)
};

// Runs one planner on the scenario. AICO: SolveAico on the problem (its collision feature's
// queries are counted) plus the validation of the result at check_resolution; RRT/BiRRT: PlanRrt
// / PlanBiRrt from q0 to goal_q with a validity checker (joint limits + InCollision, one counted
// query per state) inside the joint-limit box. `seed` seeds the RRTs' std::mt19937. OMPL
// planners: the same checker, box, goal, scenario.rrt options (range, resolution, goal_bias,
// max_checks) and seed, through OMPL (no path simplification). The AICO callback, if given, is
// forwarded.
PlanResult RunPlanner(const Scenario& scenario, Planner planner, unsigned seed,
                      const AicoCallback& callback = {});

// Total writhe and writhe matrix of the report pair at q (empty matrix if no report pair).
double ReportWritheTotal(const Scenario& scenario, const Eigen::VectorXd& q,
                         Eigen::MatrixXd* matrix = nullptr);

}  // namespace planning
