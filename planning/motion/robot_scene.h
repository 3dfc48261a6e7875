// A robot with a configuration and static objects, loaded from a URDF or a scene/scenario JSON:
// what `topoplan fk/check/render` and the viewer work on.
//
// Planning scenarios (a JSON with "robot" and "tasks", planning/motion/scenario.h) are loaded with
// LoadScenario: robot, start configuration q0 (e.g. the start coil), objects, the
// collision environment and options as the planners see them.
// Scene JSON (other keys are ignored):
//   {"robot": "robots/lwr4_sdh.urdf",          // relative to the JSON file, else to assets/
//    "q": [0, 0.5, ...],                        // optional, fk joint order; default zeros
//    "base": [x, y, z, qx, qy, qz, qw],         // optional pose of the root link (or [x, y, z])
//    "srdf": "robots/lwr4_sdh.srdf",           // optional (planning/robot/srdf.h), relative to the
//    JSON;
//                                               // default: FindSrdf next to the robot's URDF
//    "package_paths": ["../ros_ws/src"],        // optional extra package:// roots, relative to
//                                               // the JSON file's folder
//    "objects": [{"name": "pole", "urdf": "objects/pole.urdf",      // optional
//                 "position": [x, y, z] (or "xyz"), "rpy": [roll, pitch, yaw],
//                 "collide": true}, ...],      // false: drawn, but not collision-checked
//    "camera": {...}}                           // optional, used by `render` (scene_json format)
// Errors name the file and JSON path (exit 2).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/robot/robot.h"
#include "planning/robot/srdf.h"

namespace planning {

struct RobotScene {
  std::string source;  // file it was loaded from
  Robot robot;
  Eigen::VectorXd q;           // size num_dofs(robot)
  Environment env;             // every object (drawn)
  std::vector<bool> collides;  // per object of env: part of the collision environment
  // Set for planning scenarios: what the planners collide with (may replace objects by capsules)
  // and their options (disabled pairs).
  bool has_collision_env = false;
  Environment collision_env;
  CollisionOptions collision_options;
  nlohmann::json document;  // the JSON document (null for a URDF input), for optional extras
  // The robot's SRDF (--srdf, the file's "srdf", or found next to the URDF); its disabled pairs
  // are in collision_options.
  std::optional<Srdf> srdf;
  // What was accepted but is worth saying (names of the SRDF the robot lacks, ...): printed by
  // the commands as warnings, errors with --strict.
  std::vector<std::string> warnings;
  // What is worth knowing but not a problem (no SRDF found, which default configuration): printed
  // as notes (not with -q), never errors.
  std::vector<std::string> notes;
  bool q_given = false;  // q came from the file ("q" of a scene, a scenario's start)
};

// What the robot-loading flags add: --package-path (repeatable) and --srdf.
struct RobotInputOptions {
  // Tried first. Then: for a scene JSON its "package_paths", then $ROS_PACKAGE_PATH; for a
  // scenario $ROS_PACKAGE_PATH, then its "package_paths"; last the URDF's ancestor folders.
  std::vector<std::string> package_paths;
  std::string srdf;  // empty: the file's "srdf", else FindSrdf
};

// Package roots for package:// URIs: `extra` followed by the entries of $ROS_PACKAGE_PATH.
std::vector<std::string> PackagePaths(const std::vector<std::string>& extra);

// Loads `path`: a .urdf robot (q = 0, no objects), or a .json scene with a "robot" key.
RobotScene LoadRobotScene(const std::string& path, const std::vector<std::string>& package_paths);
// Same with the flags' options (ROS_PACKAGE_PATH is appended here).
RobotScene LoadRobotScene(const std::string& path, const RobotInputOptions& options);

// The configuration chosen by `--q` text or `--pose` name (a group_state of scene.srdf); neither:
// scene.q when the file gave one (q_given), else DefaultQ (said in `notes`). Throws
// std::invalid_argument when both are given or a pose has no SRDF.
// A pose value outside its joint's limits is kept and described in `warnings` when given (the
// user asked about that pose), an error otherwise.
Eigen::VectorXd ChooseQ(const RobotScene& scene, const std::string& q_text, const std::string& pose,
                        std::vector<std::string>* warnings = nullptr,
                        std::vector<std::string>* notes = nullptr);

// The configuration a robot is shown and checked in when none is asked for: the SRDF's first
// group_state if it has one, else zeros with every joint whose zero lies outside its limits at
// the middle of its limits. What was chosen is appended to `notes` (when not null) unless it is
// plain zeros.
Eigen::VectorXd DefaultQ(const RobotScene& scene, std::vector<std::string>* notes = nullptr);

// The pose of the robot's root link in the world: `--base` text "x,y,z[,qx,qy,qz,qw]" when given,
// else the free base's value in group_state `pose` (NamedBasePose), else scene.robot's
// world_from_root (a scene's "base", identity by default). Throws std::invalid_argument naming
// --base for text that is not 3 or 7 finite numbers or a zero quaternion.
Eigen::Isometry3d ChooseBase(const RobotScene& scene, const std::string& base_text,
                             const std::string& pose);

// True if `path` names something LoadRobotScene accepts: a .urdf file, or a .json whose top-level
// object has a "robot" key.
bool IsRobotSceneFile(const std::string& path);

// Parses "--q v1,...,vn" for `robot`; empty text gives zeros. Throws std::invalid_argument naming
// the flag and listing the expected joints when the count differs.
// A value outside its joint's limits is described in `warnings` when given (`check`, `fk` and
// `render` look at the pose asked about), an error otherwise.
Eigen::VectorXd ParseQ(const Robot& robot, const std::string& text,
                       std::vector<std::string>* warnings = nullptr);

// Largest |q| accepted from a file or flag (rad or m); larger values break the collision library.
inline constexpr double kMaxJointValue = 1e6;

// Throws std::invalid_argument "<where>[k] (<joint>): ..." when q[k] is not finite, |q[k]| >
// kMaxJointValue or q[k] is outside the joint's limits (1e-6 tolerance). Called for every q read
// from a flag or file, before any collision query.
void CheckJointValues(const Robot& robot, const Eigen::VectorXd& q, const std::string& where,
                      std::vector<std::string>* warnings = nullptr);

// Adds an object from "URDF[@x,y,z[,roll,pitch,yaw]]" (the `--object` flag).
void AddObjectSpec(const std::string& spec, RobotScene* scene);

// The objects of `scene` that take part in collision checks (a scenario's collision environment
// when it has one).
Environment CollisionEnvironment(const RobotScene& scene);

}  // namespace planning
