// Planning scenarios: the set-up step that turns a ScenarioSpec (scenario_spec.h: the file
// format, every key documented there) into a runnable Scenario: robot and objects loaded, the
// start and the goal resolved, the MotionProblem built. The runner is planning/motion/planner.h.
//
// Start coil: the start configuration is found by writhe continuation from q = 0 of the robot
// (the 20-link arm's zero pose is a coil around the pole): small damped Gauss–Newton steps that
// move the total writhe of writhe_report by `step` at a time under the collision and joint-limit
// tasks, until 360°·|writhe| = wrap_deg. The start is made collision-free: a continuation that
// ends in collision backs off to its last collision-free step, and one that never leaves a
// colliding q = 0 (a moved pole through the zero pose) is run again from q = 0 pushed out of
// collision first; either may stop short of wrap_deg. A start that collides, leaves the joint
// limits, ends more than 10° from wrap_deg or is no coil about the pole's line (a segment within
// `margin` of the writhe_report object's line beyond the object chain's ends, where a small move
// passes the line and the winding jumps by a turn) is retried from 32 seeded perturbations of
// q = 0 (±1 rad per joint), keeping the valid end closest to wrap_deg (it can still be short: a
// 12-link arm on a moved pole); when no end is clear of the line, the end chosen without that
// rule is kept. Scenario::warnings says when no collision-free start inside the limits, or none
// clear of the line, was found. Continuing to writhe 0 gives the "unwrapped" pose used to
// initialise the final-pose estimate (the goal). Deterministic.
//
// Goal: the final-pose estimate q̂_T (final_pose.h) from the configured init; when it misses an end
// condition of the success criteria (CheckEndState with state checks, success.h: limits, collision,
// writhe, winding, reach, box), SearchFinalPose tries the start and seeded perturbations of the
// init and keeps the estimate that meets them at least cost (or, if none does, the least
// violation).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/features/task.h"
#include "planning/motion/aico.h"
#include "planning/motion/final_pose.h"
#include "planning/motion/goal_region.h"
#include "planning/motion/rrt.h"
#include "planning/motion/scenario_spec.h"
#include "planning/robot/robot.h"

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
  // An unwrap geometry file (planning/motion/unwrap_geometry.h: pole tilt, radius, translation,
  // target offset, arm) applied to the spec before the set-up, as `bench unwrap --geometry`;
  // empty: none. Its relative arm path is looked up next to it, then under search_roots.
  std::string geometry;
};

struct SuccessCriteria {
  double writhe_total_below = -1.0;  // < 0: not checked
  // The end condition's writhe is that of the report chain closed by its chord (the writhe
  // feature's closure, writhe_feature.h), which tells the turns the chain makes round the pole
  // wherever its ends are (a whole number for an infinitely long pole). false: the open chain's.
  bool writhe_closed_by_chord = false;
  int position_task = -1;  // index into problem.tasks; −1: not checked
  double position_tolerance = 0.05;
  int box_task = -1;  // index of a "box" task whose point must end inside its box (no margin)
  // Winding of the report chain about the report object chain's line (first to last point), in
  // turns: largest change between neighbouring resampled path states, and |value| at the end.
  double winding_max_jump = -1.0;     // < 0: not checked
  double winding_final_below = -1.0;  // < 0: not checked
  // The end condition's winding is that of the report chain closed by its chord (the segment
  // from its last point back to its first), an integer number of turns about the line up to
  // rounding: w_chain − w([first, last]). false: the open chain's winding (the jump check always
  // uses the open chain).
  bool winding_closed_by_chord = false;
  // Which winding jumps are tunnelling. false ("tunnel": "line"): every jump >= winding_max_jump,
  // wherever the chain passes the line (through the pole, or round its end: the coil slipping
  // off). true ("object"): only a jump where a chain segment passes the line within the report
  // object chain's extent (first to last point), or whose pass cannot be located
  // (topology::LocateLineCrossings); a pass beyond the object's ends is then not a failure.
  bool winding_tunnel_through_object_only = false;
  // The report chain passes through the report object's closed loop at the end
  // (ChainSegmentThroughLoop, planning/motion/success.h).
  bool through_loop = false;
};

// One AICO attempt: per-task precision multipliers (size = problem.tasks), iteration limit and
// initial trajectory (rollout or q0 as aico.rollout_init says, or the unwinding path).
// Attempt 0 runs `problem` with `aico`; later ones (scenario "aico.retry") run only when the
// previous attempt fails validation or the success criteria.
struct AicoAttempt {
  Eigen::VectorXd precision_scale;
  int max_iterations = 20;
  AicoInit init = AicoInit::kDefault;  // other than kDefault: internal::UnwindingInit
};

// What changes while a scenario is planned or simulated: the objects around the robot and all
// that is built from where they are (the mjData of a Scenario; the Scenario is its mjModel). The
// collision environment, the report object chain, the task specs whose points follow an object
// (box centres, winding axis points) and the attempt-0 problem, whose features point into `env`
// and `objects` of this state. Made by SetUpScenario (Scenario::initial, the world as loaded) and
// MakeScenarioState (a copy to move), changed only by MoveObject / MoveObjectWithTargets.
// Not copyable or movable (the problem's features point into it); use unique_ptr.
struct ScenarioState {
  ScenarioState() = default;
  ScenarioState(const ScenarioState&) = delete;
  ScenarioState& operator=(const ScenarioState&) = delete;

  Environment objects;  // every object (chains, rendering)
  Environment env;      // what the robot collides with (objects, or capsules replacing them)
  // The report object chain (3 × M, world) for the report pair; empty without one.
  Eigen::Matrix3Xd report_object_chain;
  std::vector<TaskSpec> tasks;  // spec.tasks with their points where the objects are now
  MotionProblem problem;  // attempt 0: q0, tasks (targets resolved), T, dt, process parameters
};

// A set-up scenario: the model of a planning run (the mjModel to ScenarioState's mjData). Nothing
// in the library changes it once SetUpScenario returns: every planner, judge and report takes it
// as const&, and what moves lives in a ScenarioState. A caller may still set options on its own
// copy before using it (tests, benchmarks); applications hold it as const. Not movable
// (`initial.problem` points into it); use unique_ptr.
struct Scenario {
  Scenario() = default;
  Scenario(const Scenario&) = delete;
  Scenario& operator=(const Scenario&) = delete;

  // The parsed file with its frames resolved to world coordinates (ResolveSpecFrames); the tasks
  // of later attempts are built from it.
  ScenarioSpec spec;
  std::string name;
  std::string source;  // scenario file
  Robot robot;
  CollisionOptions collision;
  AicoOptions aico;
  std::vector<AicoAttempt> aico_attempts;  // at least one
  // Stop AICO at the first accepted sweep whose trajectory is a success (RunAicoAttempts).
  bool stop_when_solved = false;
  RrtOptions rrt;
  ScenarioGoalSettings rrt_goal;   // the goal-region trees' settings (goal_region.h)
  double check_resolution = 0.02;  // edge resolution for validating any output path
  Eigen::VectorXd goal_q;          // q̂_T (final-pose estimate): the RRT goal
  // The unwinding path (coil start and an "unwinding" target only, else empty): the start coil
  // continued from q0 to writhe 0, resampled at equal joint-space arc length, n × (T+1).
  Eigen::MatrixXd unwinding;
  double start_wrap_deg = 0.0;  // 360°·|writhe| of the report pair at q0
  // Writhe report pair: robot chain × object chain (for report fields and heatmaps).
  int report_chain = -1;
  SuccessCriteria success;
  // Accepted but worth saying (an SRDF's names the robot lacks, ...); commands print them as
  // warnings, errors with --strict.
  std::vector<std::string> warnings;
  // "frozen_joints": the joints held at their start values (name, value in rad or m). They are
  // fixed joints of `robot` (FreezeDofs), so q, trajectories and reports leave them out.
  std::vector<std::pair<std::string, double>> frozen;
  ScenarioState initial;  // the world as loaded: every object where the file puts it
};

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
std::unique_ptr<Scenario> LoadScenarioArg(const std::string& arg, ScenarioOverrides overrides = {});

// The MotionProblem of AICO attempt k (0 <= k < aico_attempts.size()): the scenario's tasks with
// attempt k's precision multipliers (k = 0 gives a problem equal to `problem`).
MotionProblem AttemptProblem(const Scenario& scenario, int k);
// The same with the objects (and the task points that follow them) of `state`.
MotionProblem AttemptProblem(const Scenario& scenario, const ScenarioState& state, int k);
// The AICO options of attempt k: `aico` with attempt k's iteration limit.
AicoOptions AttemptOptions(const Scenario& scenario, int k);

// Feature value y = φ(q) (dim of the feature).
Eigen::VectorXd FeatureValue(const Robot& robot, const Feature& feature, const Eigen::VectorXd& q);

// Winding number (turns) of the report chain at q about the line through the first and last
// point of the report object chain (topology::WindingNumber, signed); 0 if no report pair.
// The overloads without a state read scenario.initial.
double ReportWinding(const Scenario& scenario, const ScenarioState& state,
                     const Eigen::VectorXd& q);
double ReportWinding(const Scenario& scenario, const Eigen::VectorXd& q);
// The report chain at q, its smallest distance to that line over its points beyond the ends of
// the report object chain (topology::LineDistanceBeyondEnds), m; +infinity when no point is beyond
// them, the object chain's ends coincide or there is no report pair. Reads scenario.initial.
double ReportLineDistanceBeyondEnds(const Scenario& scenario, const Eigen::VectorXd& q);
// That line (the pole's axis in unwrap); throws std::invalid_argument if there is no report pair.
topology::Axis ReportAxis(const Scenario& scenario, const ScenarioState& state);
topology::Axis ReportAxis(const Scenario& scenario);

// Total writhe and writhe matrix of the report pair at q (empty matrix if no report pair); with
// closed_by_chord the report chain is closed by its chord first (the matrix gains a last row, the
// chord's), as the writhe feature's closure.
double ReportWritheTotal(const Scenario& scenario, const ScenarioState& state,
                         const Eigen::VectorXd& q, Eigen::MatrixXd* matrix = nullptr,
                         bool closed_by_chord = false);
double ReportWritheTotal(const Scenario& scenario, const Eigen::VectorXd& q,
                         Eigen::MatrixXd* matrix = nullptr);

// --- Moving objects (planning/motion/replan.h) ------------------------------------------------

// Names of the scenario's objects (spec order), e.g. {"ring"} or {"pole"}.
std::vector<std::string> ObjectNames(const Scenario& scenario);

// A state equal to scenario.initial (objects where the file puts them), to be moved.
std::unique_ptr<ScenarioState> MakeScenarioState(const Scenario& scenario);

// Moves object `name` of `state` to world position `position` (m; its orientation is kept):
// state->objects, the env entries made from it (the object, or its capsules "name#k"), the report
// object chain when it is the report object, and the features of state->problem
// (RebuildTaskFeatures). Task targets are kept (the goal is not re-estimated). Any workspace made
// from a problem of this state before the move holds the old pose: rebuild its feature data
// (TaskWorkspace::data, Feature::CreateData) or the workspace. Throws std::invalid_argument
// "unknown object 'X' (objects: a, b)" for an unknown name or a non-finite position.
void MoveObject(const Scenario& scenario, ScenarioState* state, const std::string& name,
                const Eigen::Vector3d& position);

// The world position of object `name` in `state`; throws as MoveObject for an unknown name.
Eigen::Vector3d ObjectPosition(const Scenario& scenario, const ScenarioState& state,
                               const std::string& name);

// Replaces the feature of every task of `problem` (built by AttemptProblem: one task per
// spec.tasks entry, in order) by one built from `state` (objects and task points where they are).
// Targets and precisions are kept. Throws std::invalid_argument on a task-count mismatch.
void RebuildTaskFeatures(const Scenario& scenario, const ScenarioState& state,
                         MotionProblem* problem);

}  // namespace planning
