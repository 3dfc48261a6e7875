// Planning scenario files (assets/scenarios/*.json) as plain data: the one place that documents
// every key. ParseScenarioSpec only reads and checks the file; planning/motion/scenario.h turns a
// spec into a runnable Scenario (robot, objects, start, goal, MotionProblem).
//
// Units: angles in radians (except wrap_deg), lengths in metres, time in seconds. Unknown keys
// anywhere are errors ("unknown key 'wrapdeg' (did you mean 'wrap_deg'?)"). Every error is a
// std::invalid_argument "<file>: <JSON path>: <what>".
//
// Relative file paths (robot, objects[].urdf) are looked up next to the scenario file first, then
// under each search root with leading "../" segments removed ("../robots/a.urdf" -> "<root>/robots/
// a.urdf"); when none exists the error lists every path tried.
//
// Root object:
//   name            string   default: the file's stem
//   description     string   free text, ignored by the planner
//   robot           string   URDF path (required; its "<stem>.chains.json" sidecar is loaded too)
//   srdf            string   SRDF path (planning/robot/srdf.h): its disable_collisions pairs are
//   added to
//                            collision.disabled_pairs and its group_states are start poses.
//                            Default: FindSrdf (NAME.srdf, ROBOT_NAME.srdf or an SRDF naming the
//                            robot, next to the URDF or in ../srdf/) if one exists
//   package_paths   [string] extra roots for package:// mesh URIs of the robot (relative ones
//                            are relative to the scenario's folder), tried before the defaults
//   objects         array    of objects, default []:
//     name          string   required, unique
//     urdf          string   URDF path (required)
//     xyz           [3]      position, m, default [0, 0, 0]
//     rpy           [3]      roll, pitch, yaw, rad (R = Rz·Ry·Rx), default [0, 0, 0]
//     frame         string   name of an EARLIER object: xyz and rpy are then in that object's
//                            frame (world pose = its world pose · this pose), so the object moves
//                            and tilts with it; default: world coordinates
//     collide       bool     default true; false: chains and rendering only
//     capsules      object   collide with capsules along a chain of the object instead of its
//                            geometry: {chain: string (required), radius: number, m (required)}
//   robot_chains    array    extra robot chains appended to the URDF's (format: chain_json.h)
//   frozen_joints   [string] joint names or SRDF group names (e.g. "gripper") held at their start
//                            values (start.q or pose; 0 for a zero or coil start) by every
//                            planner: they become fixed joints (FreezeDofs), q and trajectories
//                            leave them out, report.json lists them under "frozen_joints"
//   collision       object   self: bool (default true); disabled_pairs: [[link_a, link_b], ...];
//                            disabled_groups: [[prefix, ...], ...] (no self-collision checks
//                            between any two links whose names start with prefixes of one group;
//                            an empty prefix, or one that starts no link's name, is an error);
//                            analytic_capsules: bool (default false): capsule–capsule distances
//                            in closed form (CollisionOptions::analytic_capsules)
//   writhe_report   object   the writhe report pair: {chain: robot chain, object: object name,
//                            object_chain: chain of that object} (all strings, required)
//   start           object   required; exactly one of
//     q             [n] | "zero"   the start configuration
//     pose          string   a group_state of the robot's SRDF
//     coil          object   writhe continuation from q = 0 (needs writhe_report): small damped
//                            Gauss–Newton steps that move the report pair's total writhe by `step`
//                            under collision and joint-limit tasks until 360°·|writhe| = wrap_deg.
//                            wrap_deg: number, degrees in [0, 2000], default 720;
//                            step: number, default 0.05 (also the winding step, turns, of the
//                            "winding_then_reach" init); margin: collision margin, m, default 0.05,
//                            also the clearance kept from the object's line beyond its ends (a
//                            start nearer that line is retried; scenario.h "Start coil")
//   problem         object   T: integer 1..10000, default 50 (time steps); duration: s, default 2;
//                            dynamic: bool, default true; h_rate: default 0.1; w_rate: default
//                            1; q_rate: default 1e-10 (see MotionProblem, task.h)
//   tasks           array    required; each:
//     name          string   default "task"
//     feature       object   {type, ...}, see "Features" below (required)
//     order         integer  0 (position term, default) or 1 (velocity term)
//     target        object   default {"type": "zero"}; type: "zero" | "value" (default when
//                            "target" is given) | "interpolate" (linear from y(q0) to value) |
//                            "final_pose" (linear from y(q0) to y(goal)) | "unwinding" (y along
//                            the unwinding path: the coil continued from q0 to writhe 0, resampled
//                            at equal joint-space arc length over t = 0..T; needs a coil start);
//                            value: number (every component) or [dim] (for "value" and
//                            "interpolate"); reach_at: number in (0, 1], default 1 (for
//                            "interpolate" and "final_pose"): the target moves linearly from
//                            y(q0) to its end value until t = reach_at·T and holds it after;
//                            chord_to: name of a "position" task (for "interpolate" targets of a
//                            "writhe" feature with output "total"): value is relative to the
//                            writhe of the straight segment from the chain's first point at q0 to
//                            that task's final target, the writhe an unwrapped chain ending there
//                            has; y*_T = value + that writhe (near 0 on the shipped unwrap scene,
//                            whose base and target are at about one angle round the pole)
//                            frame: object name (for "value" and "interpolate" targets of a
//                            "position" feature, value [3]): value is a point in that object's
//                            frame (its origin: [0, 0, 0]), so moving, tilting or re-placing the
//                            object moves the target; default: world coordinates
//     precision     number   ρ for t < T, >= 0, default 0
//     final_precision number ρ at t = T, >= 0, default = precision
//     final_steps   integer  K in 1..T, default 1: final_precision on the last K slices
//                            t = T − K + 1..T (a settling phase at the end of the motion)
//     between       integer  K in 0..64, default 0 (order-0 tasks): AICO also evaluates the task
//                            at the K states interpolated between neighbouring slices (Task)
//     max_jump      number   > 0 (order-0 tasks of dim 1): AICO rejects sweeps that add jumps of
//                            the feature by max_jump or more between neighbouring states (Task)
//   final_pose      object   the goal q̂_T (thesis §4.2.2; also the RRT goal), default: the start.
//                            tasks: [task names] (required); alpha: default 0.05; prior_scale:
//                            default 1; init: "ik" (default: inverse kinematics, from the
//                            start with 16 seeded starts and collision rejection, of the end
//                            targets of the listed "position" tasks; the start when there are
//                            none or IK fails) | "start" | "unwrapped" (the coil continued to
//                            writhe 0; needs a coil start) | [n] configuration
//   success         object   what a plan must meet (every planner alike; planner.h JudgePlan).
//                            Always: the path resampled at check_resolution is collision-free and
//                            within the joint limits. writhe_total_below: |total writhe of the
//                            report pair| at the end (default: not checked); writhe_closure:
//                            "open" (default) | "chord" (that writhe with the report chain closed
//                            by its chord, as the writhe feature's closure); position: {task: name
//                            (required), tolerance: m, default 0.05}: distance of the task's
//                            feature to its final target; inside_box: name of a "box" task whose
//                            point must end inside its box (centre ± half_extent; the task's
//                            margin is for planning); winding (needs writhe_report): {max_jump:
//                            turns > 0, default 0.1; final_below: turns > 0, default 0.1;
//                            final_closure: "open" (default) | "chord"; tunnel: "line" (default)
//                            | "object"}: the winding of the report chain about the line of the
//                            object chain (its first to last point), along the resampled path,
//                            changes by less than max_jump between neighbouring states (no
//                            tunnelling through the pole, no coil slipping off its end; with
//                            "object" only passes through the object chain's extent, and jumps
//                            with no located pass, count) and ends below final_below in modulus;
//                            through_loop: bool (needs writhe_report with a closed object chain):
//                            at the end the report chain passes through the object's loop (a
//                            segment of the chain crosses the disc the loop bounds, success.h
//                            ChainSegmentThroughLoop)
//   aico            object   max_iterations: integer >= 1, default 20; tolerance: default 0.01;
//                            damping: default 1; sweep_mode: "forwardly" (default) | "symmetric"
//                            | "local_gauss_newton"; max_step: rad, default 1;
//                            max_relocations: integer in [1, 100], default 5;
//                            relocation_damping: in [1e-6, 1], default 0.3; rollout_init:
//                            bool, default false; rollout_prior: default 100;
//                            rollout_iterations: integer >= 1, default 10 (see aico.h);
//                            stop_when_solved: bool, default false: after every accepted sweep
//                            whose last slice meets the end conditions, validate and judge the
//                            trajectory (as a finished plan, counted) and stop at the first that
//                            is a success (status "solved"; planner.h RunAicoAttempts)
//     retry         object   a second attempt when the first fails validation or the success
//                   or array  criteria (an array: one attempt per entry, each run when the ones
//                            before it failed): precision_scale: {task name: factor > 0, ...}
//                            (default {}); max_iterations: integer >= 1, default
//                            aico.max_iterations; init (needs writhe_report; its queries are
//                            counted, planner.h RunAicoAttempts): "unwinding": start from the
//                            writhe continuation of q0 to 0 resampled to the slices;
//                            "unwinding_then_reach": the same continuation also under the
//                            attempt's line_clearance tasks, then the hand moved to the final
//                            targets of the position tasks with the writhe held (start_coil.h);
//                            "winding_then_reach": as unwinding_then_reach, the continuation
//                            stepping the winding about the pole's line to 0 instead of the
//                            writhe (the line through the ends of the writhe_report's object
//                            chain; ends that coincide are refused); absent: as the first
//                            attempt
//   rrt             object   range: rad, default 0 (auto); resolution: rad, default 0 (auto);
//                            goal_bias: default 0.1; max_checks: integer >= 1, default 100000;
//                            goal_states: integer 1..10000, default 32 (the goal-region trees'
//                            most goal states: rrt-region's and ompl-rrt-region's pool,
//                            birrt-region's goal roots; goal_region.h max_goal_states);
//                            goal_ik_iterations: integer 1..100000, default 200, and
//                            goal_ik_starts: integer 1..100, default 1 (the goal sampler's IK
//                            iterations per start and uniform starts per draw, for every
//                            goal-region planner; scenario_goal_region.h; OMPL's goal-draw cap
//                            counts draws, so one draw may cost up to goal_ik_starts IK solves)
//   check_resolution number  edge resolution (rad) for validating output paths, default
//                            rrt.resolution if > 0, else 0.02
//
// Frames: a "frame" names an object of "objects"; an unknown name is an error naming the key
// ("<file>: tasks[5].target.frame: unknown object 'polee' (objects: pole, cylinder) (did you
// mean 'pole'?)"). SetUpScenario resolves every frame to world coordinates (ResolveSpecFrames) from
// the object placements as they are then, so a caller that moves an object in the spec before the
// set-up (the unwrap benchmark's pole offset and geometries) moves what is placed in its frame.
//
// Value limits (checked when read; the message names the JSON path): every number is finite;
// check_resolution and a non-zero rrt.resolution >= 1e-6 (check_resolution <= 10); rrt.range and
// rrt.resolution <= 1000; goal_bias in [0, 1]; max_checks <= 1e9; aico max_iterations and
// rollout_iterations <= 100000; precisions, rates, damping, priors and retry factors <= 1e12
// (h_rate, w_rate >= 1e-12); duration in [1e-3, 1e4]; coil step in [1e-3, 10]; radii, margins and
// tolerances in [0, 10]; aico tolerance in [1e-12, 1e6], max_step in [1e-9, 1000].
//
// Features (the keys besides "type"):
//   position        link (required), offset [3] (default 0)
//   axis_alignment  link (required), axis [3] (default [0, 0, 1]), direction [3] (required;
//                   with frame: an object name, a direction in that object's frame)
//   joint_limits    margin (rad, default 0: revolute and continuous joints), prismatic_margin
//                   (m, default 0: prismatic joints); each capped at 45 % of its joint's range
//   joint_position  (none)
//   box             link (required), offset [3] (default 0), center [3], half_extent [3]
//                   (required), margin (m, default 0), frame (object name: center is a point in
//                   that object's frame; the box's axes stay the world's)
//   writhe          chain, object, object_chain (required), output: "matrix" (default) | "total",
//                   closure: "open" (default) | "chord" (the chain closed by its chord from its
//                   last point back to its first: writhe_feature.h)
//   winding         chain (required), and either axis_point [3] and axis_direction [3] (with
//                   frame: an object name, both in that object's frame), or object and
//                   object_chain (the line through that chain's first and last point)
//   collision       margin (m, default 0.05)
//   line_clearance  chain, object, object_chain (required), margin (m, default 0.05): the robot
//                   chain's segments kept `margin` off the line through the first and last point
//                   of the object chain (MakeLineClearanceFeature)
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/enum_names.h"
#include "planning/features/feature.h"
#include "planning/motion/aico.h"
#include "planning/motion/final_pose.h"
#include "planning/motion/goal_region.h"
#include "planning/motion/rrt.h"
#include "planning/robot/chain_json.h"

namespace planning {

// A name read from the file (link, chain, object, task) and where: "<file>: <JSON path>".
struct SpecName {
  std::string name;
  std::string where;
};

struct ObjectSpec {
  std::string name;
  std::string urdf;  // resolved path (exists)
  std::string where;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  bool collide = true;
  std::optional<SpecName> frame;  // xyz/rpy in the frame of this (earlier) object; unset: world
  std::optional<SpecName> capsule_chain;  // set: collide with capsules along this chain
  double capsule_radius = 0.0;
};

struct CollisionSpec {
  bool self = true;
  std::vector<std::pair<std::string, std::string>> disabled_pairs;
  std::vector<std::vector<std::string>> disabled_groups;  // link-name prefixes
  bool analytic_capsules = false;
  std::string where;  // empty: no "collision" key
  // "<file>: <JSON path>" of disabled_groups, where its errors point ("<groups_where>[0][1]: ...");
  // empty: "collision.disabled_groups".
  std::string groups_where;
};

struct WritheReportSpec {
  SpecName chain, object, object_chain;
};

enum class StartKind { kQ, kZero, kCoil, kPose };
struct StartSpec {
  StartKind kind = StartKind::kZero;
  Eigen::VectorXd q;  // kQ (size checked against the robot at set-up)
  std::string pose;   // kPose: group_state name (checked against the SRDF at set-up)
  double wrap_deg = 720.0;
  double step = 0.05;
  double margin = 0.05;
  std::string where;  // of "start" ("start.q" for kQ)
};

struct ProblemSpec {
  int num_steps = 50;
  double duration = 2.0;
  bool dynamic = true;
  double h_rate = 0.1;
  double w_rate = 1.0;
  double q_rate = 1e-10;
};

enum class FeatureType {
  kPosition,
  kAxisAlignment,
  kJointLimits,
  kJointPosition,
  kBox,
  kWrithe,
  kWinding,
  kCollision,
  kLineClearance
};
inline constexpr base::EnumName<FeatureType> kFeatureTypeNames[] = {
    {FeatureType::kPosition, "position"},
    {FeatureType::kAxisAlignment, "axis_alignment"},
    {FeatureType::kJointLimits, "joint_limits"},
    {FeatureType::kJointPosition, "joint_position"},
    {FeatureType::kBox, "box"},
    {FeatureType::kWrithe, "writhe"},
    {FeatureType::kWinding, "winding"},
    {FeatureType::kCollision, "collision"},
    {FeatureType::kLineClearance, "line_clearance"},
};
constexpr std::span<const base::EnumName<FeatureType>> EnumNames(FeatureType) {
  return kFeatureTypeNames;
}

struct FeatureSpec {
  FeatureType type = FeatureType::kJointPosition;
  std::string where;
  SpecName link, chain, object, object_chain;  // as the type needs
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_extent = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_direction = Eigen::Vector3d::Zero();
  double margin = 0.0;            // the type's default when absent (collision: 0.05)
  double prismatic_margin = 0.0;  // joint_limits: the margin of prismatic joints, m
  WritheOutput output = WritheOutput::kMatrix;
  bool closed_by_chord = false;  // writhe: "closure": "chord" (default "open")
  // box: center; winding: axis_point and axis_direction; axis_alignment: direction, in the frame
  // of this object (unset: world).
  std::optional<SpecName> frame;
};

enum class TargetKind { kZero, kValue, kInterpolate, kFinalPose, kUnwinding };
inline constexpr base::EnumName<TargetKind> kTargetKindNames[] = {
    {TargetKind::kZero, "zero"},
    {TargetKind::kValue, "value"},
    {TargetKind::kInterpolate, "interpolate"},
    {TargetKind::kFinalPose, "final_pose"},
    {TargetKind::kUnwinding, "unwinding"},
};
constexpr std::span<const base::EnumName<TargetKind>> EnumNames(TargetKind) {
  return kTargetKindNames;
}

struct TargetSpec {
  TargetKind kind = TargetKind::kZero;
  Eigen::VectorXd value;  // kValue / kInterpolate
  bool scalar = false;    // value was one number: every component
  double reach_at = 1.0;  // kInterpolate / kFinalPose: fraction of T at which y_T is reached
  std::optional<SpecName> frame;     // value is a point in this object's frame (unset: world)
  std::optional<SpecName> chord_to;  // a position task: value is relative to the chord's writhe
  std::string where;                 // of "target"
  std::string value_where;
};

struct TaskSpec {
  std::string name = "task";
  FeatureSpec feature;
  int order = 0;
  int between = 0;
  double max_jump = 0.0;
  double precision = 0.0;
  double final_precision = 0.0;
  int final_steps = 1;  // final_precision on the last final_steps slices (<= T, checked at set-up)
  std::string final_steps_where;  // of "final_steps" (empty: not given)
  TargetSpec target;
  std::string where;
};

enum class FinalPoseInit { kStart, kUnwrapped, kQ, kIk };
struct FinalPoseSpec {
  std::vector<SpecName> tasks;  // empty: the goal is the start
  FinalPoseOptions options;
  FinalPoseInit init = FinalPoseInit::kStart;
  Eigen::VectorXd init_q;
  std::string init_where;
};

struct SuccessSpec {
  double writhe_total_below = -1.0;     // < 0: not checked
  bool writhe_closed_by_chord = false;  // "writhe_closure": "chord" (default "open")
  std::optional<SpecName> position_task;
  double position_tolerance = 0.05;
  std::optional<SpecName> box_task;
  double winding_max_jump = -1.0;                   // turns; < 0: not checked
  double winding_final_below = -1.0;                // turns; < 0: not checked
  bool winding_closed_by_chord = false;             // "final_closure": "chord" (default "open")
  bool winding_tunnel_through_object_only = false;  // "tunnel": "object" (default "line")
  std::string winding_where;                        // of "success.winding" (empty: not given)
  bool through_loop = false;       // the report chain must end through the report loop
  std::string through_loop_where;  // of "success.through_loop" (empty: not given)
};

// The initial trajectory of an AICO attempt ("init" of an aico.retry entry; each needs a
// writhe_report; internal/start_coil.h builds them).
enum class AicoInit {
  kDefault,    // absent: as attempt 0 (aico.rollout_init: the rollout, or q0 held)
  kUnwinding,  // "unwinding": the writhe continuation of q0 to writhe 0
  // "unwinding_then_reach": the same continuation also kept off the pole's line (the attempt's
  // line_clearance tasks not switched off), then the hand moved to its final targets with the
  // writhe held
  kUnwindingThenReach,
  // "winding_then_reach": as unwinding_then_reach, with the continuation stepping the winding
  // about the pole's line (ReportWinding) to 0 instead of the writhe
  kWindingThenReach,
};
inline constexpr base::EnumName<AicoInit> kAicoInitNames[] = {
    {AicoInit::kUnwinding, "unwinding"},
    {AicoInit::kUnwindingThenReach, "unwinding_then_reach"},
    {AicoInit::kWindingThenReach, "winding_then_reach"},
};
constexpr std::span<const base::EnumName<AicoInit>> EnumNames(AicoInit) { return kAicoInitNames; }

// One AICO attempt: task precisions scaled by name, its iteration limit and its initial
// trajectory.
struct AicoAttemptSpec {
  std::vector<std::pair<SpecName, double>> precision_scale;
  int max_iterations = 20;
  AicoInit init = AicoInit::kDefault;
  std::string init_where;  // of "init", for messages
};

struct ScenarioSpec {
  std::string name;
  std::string source;  // the scenario file
  std::string robot;   // resolved URDF path
  // Where errors in loading `robot` point: "<source>: robot" when empty (an unwrap geometry's arm
  // sets "<geometry file>: arm.urdf").
  std::string robot_where;
  std::string srdf;  // resolved SRDF path; empty: FindSrdf(robot) at set-up
  // Resolved "package_paths".
  std::vector<std::string> package_paths;
  std::vector<ObjectSpec> objects;
  std::vector<ChainDescription> robot_chains;
  // "frozen_joints": joint names or SRDF group names held at their start values by every planner.
  std::vector<std::string> frozen_joints;
  std::string frozen_where;  // JSON path, for messages
  CollisionSpec collision;
  std::optional<WritheReportSpec> writhe_report;
  StartSpec start;
  ProblemSpec problem;
  std::vector<TaskSpec> tasks;
  FinalPoseSpec final_pose;
  SuccessSpec success;
  AicoOptions aico;
  std::vector<AicoAttemptSpec> aico_attempts;  // [0]: plain; [1..]: the "aico.retry" entries
  bool aico_stop_when_solved = false;
  RrtOptions rrt;
  ScenarioGoalSettings rrt_goal;  // rrt.goal_states, rrt.goal_ik_iterations, rrt.goal_ik_starts
  double check_resolution = 0.02;
};

// Reads and checks a scenario file (see above). Throws std::invalid_argument.
ScenarioSpec ParseScenarioSpec(const std::string& path,
                               const std::vector<std::string>& search_roots = {});

// World pose of spec.objects[i]: its xyz/rpy composed with the world poses of its "frame" parents.
// Throws std::out_of_range for i out of range.
Eigen::Isometry3d ObjectWorldPose(const ScenarioSpec& spec, size_t i);

// Every frame-relative placement of `spec` in world coordinates, from the object placements as
// they are now: objects get their world xyz/rpy (ObjectWorldPose), target values of position
// tasks become world points p_w = T_object · p, box centres and winding axis points too,
// axis_alignment directions and winding axis directions rotated by R_object; then every frame is
// cleared, so the spec equals one written in world coordinates (a second call changes nothing).
// SetUpScenario calls it. Throws std::invalid_argument naming the key for a frame that names no
// object.
void ResolveSpecFrames(ScenarioSpec* spec);

// A relative `file` next to `base_dir`, else under each search root (leading "../" removed);
// absolute paths as given. Throws "<where>: cannot find '<file>' (tried: a, b, ...)".
std::string ResolveDataFile(const std::string& file, const std::string& base_dir,
                            const std::vector<std::string>& search_roots, const std::string& where);

}  // namespace planning
