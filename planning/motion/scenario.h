// Planning scenarios: the set-up step that turns a ScenarioSpec (scenario_spec.h: the file
// format, every key documented there) into a runnable Scenario: robot and objects loaded, the
// start and the goal resolved, the MotionProblem built. The runner is planning/motion/planner.h.
//
// Start coil: the start configuration is found by writhe continuation from q = 0 of the robot
// (the 20-link arm's zero pose is a coil around the pole): small damped Gauss–Newton steps that
// move the total writhe of writhe_report by `step` at a time under the collision and joint-limit
// tasks, until 360°·|writhe| = wrap_deg. Continuing to writhe 0 gives the "unwrapped" pose used to
// initialise the final-pose estimate (the goal). Deterministic.
//
// Goal: the final-pose estimate q̂_T (final_pose.h) from the configured init; when it misses an end
// condition of the success criteria (CheckEndState with state checks: limits, collision, writhe,
// winding, reach, box), SearchFinalPose tries the start and seeded perturbations of the init and
// keeps the estimate that meets them at least cost (or, if none does, the least violation).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "planning/motion/aico.h"
#include "planning/collision/collision.h"
#include "planning/motion/final_pose.h"
#include "planning/robot/robot.h"
#include "planning/motion/rrt.h"
#include "planning/motion/scenario_spec.h"
#include "planning/features/task.h"

namespace planning {

struct ScenarioOverrides {
  std::optional<double> start_wrap_deg;  // replaces start.coil.wrap_deg
  std::optional<bool> stop_when_solved;  // replaces aico.stop_when_solved
  // Where relative robot/object URDF paths are looked up after the scenario's own folder.
  std::vector<std::string> search_roots;
  // Extra package:// roots (tried before the file's "package_paths"), and an SRDF that replaces
  // the file's "srdf" (planning/robot/srdf.h) when not empty.
  std::vector<std::string> package_paths;
  std::string srdf;
};

struct SuccessCriteria {
  double writhe_total_below = -1.0;  // < 0: not checked
  int position_task = -1;            // index into problem.tasks; −1: not checked
  double position_tolerance = 0.05;
  int box_task = -1;  // index of a "box" task whose point must end inside its box (no margin)
  // Winding of the report chain about the report object chain's line (first to last point), in
  // turns: largest change between neighbouring resampled path states, and |value| at the end.
  double winding_max_jump = -1.0;     // < 0: not checked
  double winding_final_below = -1.0;  // < 0: not checked
};

// One AICO attempt: per-task precision multipliers (size = problem.tasks) and iteration limit.
// Attempt 0 runs `problem` with `aico`; later ones (scenario "aico.retry") run only when the
// previous attempt fails validation or the success criteria.
struct AicoAttempt {
  Eigen::VectorXd precision_scale;
  int max_iterations = 20;
};

// A set-up scenario. Not movable (the problem and features point into it); use unique_ptr.
struct Scenario {
  Scenario() = default;
  Scenario(const Scenario&) = delete;
  Scenario& operator=(const Scenario&) = delete;

  ScenarioSpec spec;  // the parsed file (tasks of later attempts are built from it)
  std::string name;
  std::string source;  // scenario file
  Robot robot;
  Environment objects;  // every object (chains, rendering)
  Environment env;      // what the robot collides with (objects, or capsules replacing them)
  CollisionOptions collision;
  MotionProblem problem;  // attempt 0: q0, tasks (targets resolved), T, dt, process parameters
  AicoOptions aico;
  std::vector<AicoAttempt> aico_attempts;  // at least one
  // Stop AICO at the first accepted sweep whose trajectory is a success (RunAicoAttempts).
  bool stop_when_solved = false;
  RrtOptions rrt;
  double check_resolution = 0.02;  // edge resolution for validating any output path
  Eigen::VectorXd goal_q;          // q̂_T (final-pose estimate): the RRT goal
  // The unwinding path (coil start and an "unwinding" target only, else empty): the start coil
  // continued from q0 to writhe 0, resampled at equal joint-space arc length, n × (T+1).
  Eigen::MatrixXd unwinding;
  double start_wrap_deg = 0.0;  // 360°·|writhe| of the report pair at q0
  // Writhe report pair: robot chain × object chain (for report fields and heatmaps).
  int report_chain = -1;
  Eigen::Matrix3Xd report_object_chain;
  SuccessCriteria success;
};

// The end conditions of the success criteria at one configuration q (what JudgePlan checks at a
// path's last state) and, with `state_checks`, the state itself (joint limits, InCollision).
struct EndState {
  bool within_limits = true;   // (state_checks only)
  bool collision_free = true;  // (state_checks only)
  double writhe_total = 0.0;   // ReportWritheTotal(q)
  double winding_turns = 0.0;  // ReportWinding(q) (with the winding criterion only, else 0)
  // The writhe matrix entry of largest |W_ij| (row = robot chain segment, col = object segment;
  // −1 and 0 when there is no report pair).
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
EndState CheckEndState(const Scenario& scenario, const Eigen::VectorXd& q, bool state_checks);

// The expensive part of a set-up, computed from the spec alone: the start q0 (n), the unwinding
// path (n × (T+1), or empty) and the goal q̂_T (n). ResolvedPosesOf(scenario) reads them back; a
// later SetUpScenario of the same spec given them skips the start-coil continuation and the
// final-pose estimate and builds a scenario equal to the first (e.g. set up once, then shipped to
// other processes of a sweep).
struct ResolvedPoses {
  Eigen::VectorXd q0;
  Eigen::MatrixXd unwinding;
  Eigen::VectorXd goal_q;
};
ResolvedPoses ResolvedPosesOf(const Scenario& scenario);

// Sets up a parsed scenario (loads the robot and objects, runs the start-coil continuation and
// the final-pose estimate, or takes both from `resolved` when given: then start_wrap_deg is not
// used). Name errors (unknown links, chains, objects, tasks) name the JSON path; `resolved` of
// the wrong sizes or with non-finite values throws std::invalid_argument.
std::unique_ptr<Scenario> SetUpScenario(ScenarioSpec spec,
                                        const std::optional<double>& start_wrap_deg = {},
                                        const ResolvedPoses* resolved = nullptr);

// ParseScenarioSpec(path, overrides.search_roots) + SetUpScenario.
std::unique_ptr<Scenario> LoadScenario(const std::string& path,
                                       const ScenarioOverrides& overrides = {});

// A scenario argument as users give it: a file path, or a bare name looked up as
// <assets>/scenarios/NAME.json (base::ResolveScenarioPath), loaded with the asset root as the
// search root for its relative robot/object paths (so a copy of a shipped scenario loads from
// any folder).
std::unique_ptr<Scenario> LoadScenarioArg(const std::string& arg,
                                          ScenarioOverrides overrides = {});

// The MotionProblem of AICO attempt k (0 <= k < aico_attempts.size()): the scenario's tasks with
// attempt k's precision multipliers (k = 0 gives a problem equal to `problem`).
MotionProblem AttemptProblem(const Scenario& scenario, int k);
// The AICO options of attempt k: `aico` with attempt k's iteration limit.
AicoOptions AttemptOptions(const Scenario& scenario, int k);

// Feature value y = φ(q) (dim of the feature).
Eigen::VectorXd FeatureValue(const Robot& robot, const Feature& feature, const Eigen::VectorXd& q);

// Winding number (turns) of the report chain at q about the line through the first and last
// point of the report object chain (topology::WindingNumber, signed); 0 if no report pair.
double ReportWinding(const Scenario& scenario, const Eigen::VectorXd& q);
// That line (the pole's axis in unwrap); throws std::invalid_argument if there is no report pair.
topology::Axis ReportAxis(const Scenario& scenario);

// Total writhe and writhe matrix of the report pair at q (empty matrix if no report pair).
double ReportWritheTotal(const Scenario& scenario, const Eigen::VectorXd& q,
                         Eigen::MatrixXd* matrix = nullptr);

// --- Moving objects (planning/motion/replan.h) ------------------------------------------------------

// Names of the scenario's objects (spec order), e.g. {"ring"} or {"pole"}.
std::vector<std::string> ObjectNames(const Scenario& scenario);

// Moves object `name` to world position `position` (m; its orientation is kept): `objects`, the
// `env` entries made from it (the object, or its capsules "name#k"), spec.objects[].xyz, the
// report object chain when it is the report object, and the features of `problem`
// (RebuildTaskFeatures). Task targets are kept (the goal is not re-estimated). Any workspace
// made from a problem of this scenario before the move holds the old pose: rebuild its feature
// data (TaskWorkspace::data, Feature::CreateData) or the workspace. Throws std::invalid_argument
// "unknown object 'X' (objects: a, b)" for an unknown name or a non-finite position.
void MoveObject(Scenario* scenario, const std::string& name, const Eigen::Vector3d& position);

// Replaces the feature of every task of `problem` (built by AttemptProblem: one task per
// spec.tasks entry, in order) by one built from the scenario as it is now (objects where they
// are). Targets and precisions are kept. Throws std::invalid_argument on a task-count mismatch.
void RebuildTaskFeatures(const Scenario& scenario, MotionProblem* problem);

}  // namespace planning
