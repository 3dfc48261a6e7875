// Loading robots (and single-link objects) from URDF files, meshes through assimp, chains from a
// sidecar JSON file. The only code that reads robot files; kinematics never touches files.
//
// URDF support (parsed with urdfdom, validated first with our own pass for clear messages):
//   - joints: revolute, continuous, prismatic, fixed, with <mimic joint= multiplier= offset=>;
//     floating and planar joints are rejected (model a free base with 6 joints instead);
//   - geometry: box, sphere, cylinder, mesh (STL, DAE or OBJ through assimp;
//     read by planning/robot/mesh_io.h, which states the axes and units, once per file and robot).
//     A <collision> or <visual> whose name starts with "capsule" and holds a <cylinder> is loaded
//     as a capsule of that radius whose cap centres are `length` apart (URDF has no capsule);
//   - mesh filenames: "package://PKG/rel", "file:///abs", absolute, or relative to the URDF's
//     folder. package:// URIs are resolved by trying DIR/PKG/rel for each DIR in
//     RobotLoadOptions::package_paths, then each ancestor folder of the URDF file (so a standard
//     ROS package layout works without configuration). The resolved file (symbolic links
//     followed) must lie inside the package folder: "package://pkg/../../etc/x" is refused;
//     when a package folder is found but the file is not, the message names every file tried;
//   - colours from <material><color rgba=>, also by reference to a top-level <material>.
// Errors (all std::invalid_argument, message starts with the file name and, where known, the
// line): unreadable file, XML errors, missing or duplicate link/joint names, a joint whose
// parent or child link does not exist, a link with two parents, cycles, no or several roots,
// unknown joint types, mimic of an unknown joint, missing mesh files, meshes assimp cannot read,
// XML nested deeper than 100 elements (checked on the text, before any XML parser runs), more
// than kMaxUrdfLinks links, and any <visual>/<collision> urdfdom would drop with only a log line:
// a missing or empty <geometry>, an unknown shape, attributes that are not exactly the expected
// count of finite numbers (box size, sphere/cylinder radius and length, mesh scale, origin xyz
// and rpy), a mesh without filename; also a capsule with radius <= 0. Tree checks (roots, cycles,
// mimic chains) are linear in the number of links and joints.
//
// Chain sidecar (optional): `<urdf path without .urdf>.chains.json`, or an explicit path:
//   {"chains": [{"name": "arm", "closed": false,
//                "points": [{"link": "link1", "xyz": [0, 0, 0.1]}, ...]}, ...]}
// Each point is a position in the named link's frame. Errors name the file and JSON path.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "planning/robot/robot.h"

namespace planning {

// Most links a URDF may have.
inline constexpr size_t kMaxUrdfLinks = 100000;

struct RobotLoadOptions {
  std::vector<std::string> package_paths;  // extra roots for package:// URIs (tried first)
  bool load_meshes = true;                 // false: mesh geometry is dropped, files not read
  // Chain sidecar file. Empty: use `<stem>.chains.json` next to the URDF if it exists.
  std::string chains_path;
};

// Loads a URDF file. See the file comment for the accepted subset and the errors thrown.
Robot LoadRobot(const std::string& urdf_path, const RobotLoadOptions& options = {});

// Same, from a string; `source_name` is used in messages and relative paths resolve against
// `base_dir`.
Robot ParseRobot(const std::string& urdf_xml, const std::string& source_name,
                 const std::string& base_dir, const RobotLoadOptions& options = {});

// Reads chains from a sidecar JSON file into robot->chains (appending). Throws
// std::invalid_argument naming the file and JSON path (e.g. "chains[2].points[0].link").
void LoadChains(const std::string& json_path, Robot* robot);

}  // namespace planning
