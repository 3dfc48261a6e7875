// Geometries of the unwrap generalisation study (`topoplan bench unwrap --geometry FILE`): the
// shipped unwrap scenario with its pole tilted, resized and moved, its reach target moved and
// another arm, all with the scenario's planner parameters unchanged (a frozen set-up).
//
// Geometry file (JSON; every key optional, unknown keys are errors naming the JSON path):
//   name              string   default: the file's stem; letters, digits, '_', '-' and '.' only
//                              (it is the first column of geometry.csv), the stem too
//   split             string   "tuning" | "test" (default "test"): which set the geometry belongs
//                              to (assets/scenarios/unwrap_geometries/README.md); informational
//   pole_tilt_deg     [2]      rotations about the pole's own x and then y axis, through its origin
//                              (the pole's centre), degrees in [-90, 90]: R = R_pole · Rx(a) ·
//                              Ry(b)
//   pole_radius       number   m in [0.005, 0.5]: the pole collides as capsules of this radius
//   along
//                              the report object chain (objects[].capsules), instead of its URDF
//                              geometry (radius 0.03). Default: the scenario's pole
//   pole_translation  [3]      m, world, each in [-1, 1]: added to the pole's xyz
//   target_offset     [3]      m, in the pole's frame, each in [-1, 1]: added to the placement of
//                              the reach target's frame object (the cylinder, placed in the pole's
//                              frame), or to the target itself when its frame is the pole
//   arm               object   {urdf: path (required; relative to this file, then the search
//   roots),
//                              disabled_groups: [[prefix, ...], ...] (replaces the scenario's
//                              collision.disabled_groups; default: kept; each prefix non-empty
//                              and starting some link's name)}: the robot
//
// Moving the pole moves what the scenario places in its frame (scenario_spec.h "Frames").
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "planning/motion/scenario_spec.h"

namespace planning {

struct UnwrapGeometry {
  std::string name;
  std::string source;  // the geometry file
  std::string split = "test";
  Eigen::Vector2d pole_tilt_deg = Eigen::Vector2d::Zero();  // about the pole's x, then y [deg]
  double pole_radius = 0.0;                                 // [m]; 0: the scenario's pole geometry
  Eigen::Vector3d pole_translation = Eigen::Vector3d::Zero();  // world [m]
  Eigen::Vector3d target_offset = Eigen::Vector3d::Zero();     // pole frame [m]
  std::string arm_urdf;        // resolved path; empty: the scenario's robot
  std::string arm_urdf_where;  // "<file>: arm.urdf" (errors in loading it name the entry)
  std::optional<std::vector<std::vector<std::string>>> arm_disabled_groups;
  std::string arm_disabled_groups_where;  // "<file>: arm.disabled_groups" (errors name entries)
};

// Reads a geometry file (see above). Relative arm paths are looked up next to the file, then
// under each search root (ResolveDataFile). Throws std::invalid_argument "<file>: <path>: <what>".
UnwrapGeometry ReadUnwrapGeometry(const std::string& path,
                                  const std::vector<std::string>& search_roots = {});

// `spec` (an unwrap scenario: its writhe_report object is the pole) with geometry `g` applied:
// the pole's rpy tilted and xyz translated, its collision radius set, the reach target moved, the
// robot replaced. Throws std::invalid_argument when the scenario has no coil start (not an unwrap
// scenario) or no writhe_report object, and
// for a target_offset when the success criterion's position task has no target placed in the
// pole's frame (directly or through an object placed in it).
void ApplyUnwrapGeometry(const UnwrapGeometry& g, ScenarioSpec* spec);

}  // namespace planning
