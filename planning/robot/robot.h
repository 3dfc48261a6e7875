// The immutable robot model: links, joints, geometry, meshes and named chains.
//
// A Robot is built once (by planning/robot/robot_io.h from a URDF file) and never changes
// afterwards; everything that depends on a configuration q lives in a workspace (KinematicsData in
// planning/robot/kinematics.h, CollisionData in planning/collision/collision.h).
//
// Conventions:
//   - Links are stored in topological order: links[0] is the root (the world frame at q = 0 is the
//     root link's frame), and every link comes after its parent. Each non-root link has exactly
//     one parent joint.
//   - q (the configuration) holds the *independent movable joints*: revolute, continuous and
//     prismatic joints that are not mimic joints, in the order their <joint> elements appear in
//     the URDF file. robot.dof_joints[k] is the joint driven by q[k]; joint names in that order are
//     what `topoplan fk` prints as "joints". Mimic joints follow their master:
//     value = multiplier · q[master] + offset.
//   - Angles in radians, lengths in metres. Joint axes are unit vectors in the joint frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "base/enum_names.h"

namespace planning {

enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic };

// How the robot stands in the world. kFixed: bolted down. kFloating / kPlanar: a free base (a URDF
// floating/planar joint below the root link, or an SRDF virtual_joint of that type): its pose is
// not part of q (planners keep it where it is); Robot::world_from_root places the robot.
enum class BaseType { kFixed, kFloating, kPlanar };
inline constexpr base::EnumName<BaseType> kBaseTypeNames[] = {
    {BaseType::kFixed, "fixed"}, {BaseType::kFloating, "floating"}, {BaseType::kPlanar, "planar"}};
constexpr std::span<const base::EnumName<BaseType>> EnumNames(BaseType) { return kBaseTypeNames; }

// Joint limits. Continuous and fixed joints have lower = −∞, upper = +∞.
struct JointLimits {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  double velocity = std::numeric_limits<double>::infinity();  // rad/s or m/s; ∞ if not given
  double effort = std::numeric_limits<double>::infinity();    // N·m or N; ∞ if not given
};

struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;  // index into Robot::links
  int child_link = -1;   // index into Robot::links
  // Pose of the joint frame in the parent link frame (the URDF <origin>). The child link frame
  // equals the joint frame moved by the joint: child = origin · Rot(axis, v) or origin ·
  // Trans(axis·v).
  Eigen::Isometry3d parent_from_joint = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, in the joint frame
  JointLimits limits;
  // Index of q that drives this joint: its own entry for an independent movable joint, the
  // (transitively resolved) master's entry for a mimic joint, −1 for a fixed joint.
  int dof = -1;
  bool is_mimic = false;
  double mimic_multiplier = 1.0;  // joint value = mimic_multiplier · q[dof] + mimic_offset
  double mimic_offset = 0.0;
};

// One piece of collision or visual geometry, attached to a link (or to an object).
struct Geometry {
  enum class Kind { kBox, kSphere, kCylinder, kCapsule, kMesh };
  Kind kind = Kind::kSphere;
  // kBox: full side lengths (x, y, z). kSphere: (radius, 0, 0). kCylinder: (radius, length, 0),
  // axis = local z, centred. kCapsule: (radius, length, 0), the segment between the two cap
  // centres runs along local z from −length/2 to +length/2. kMesh: per-axis scale.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  int mesh = -1;  // kMesh only: index into Robot::meshes
  Eigen::Isometry3d link_from_geometry = Eigen::Isometry3d::Identity();
  std::array<float, 4> rgba{0.7f, 0.7f, 0.7f, 1.0f};  // linear RGBA in [0, 1] (visuals)
};

// A triangle mesh read by planning/robot/mesh_io.h (all meshes of the file merged, node transforms
// applied, z up, metres; the Geometry's scale is applied on top).
struct Mesh {
  std::string path;                        // resolved file path
  std::vector<Eigen::Vector3f> vertices;   // mesh frame
  std::vector<Eigen::Vector3f> normals;    // per vertex (same size as vertices), unit
  std::vector<Eigen::Vector3i> triangles;  // counter-clockwise vertex indices
};

struct Link {
  std::string name;
  int parent_joint = -1;  // −1 for the root link
  std::vector<Geometry> visuals;
  std::vector<Geometry> collisions;
};

// A chain: a named polyline attached to links, used by the writhe and winding features. Point k is
// point_local.col(k) expressed in the frame of links[point_link[k]]. If `closed`, consumers that
// need a closed curve repeat point 0 at the end (ChainPoints does this; see kinematics.h).
struct ChainSpec {
  std::string name;
  std::vector<int> point_link;   // size N, indices into Robot::links
  Eigen::Matrix3Xd point_local;  // 3 × N
  bool closed = false;
};

struct Robot {
  std::string name;
  std::string source;  // the file it was loaded from (for messages)
  std::vector<Link> links;
  std::vector<Joint> joints;    // any order; joints[links[i].parent_joint].child_link == i
  std::vector<int> dof_joints;  // size num_dofs: joint index driven by q[k], in q order
  std::vector<Mesh> meshes;
  std::vector<ChainSpec> chains;
  // Pose of links[0] in the world (ForwardKinematics starts from it): identity unless a base pose
  // is given (`--base`, a scene's "base", an SRDF group_state value of the free base). Any robot
  // can be placed; only a free base makes the pose part of what a file describes.
  Eigen::Isometry3d world_from_root = Eigen::Isometry3d::Identity();
  BaseType base_type = BaseType::kFixed;
  std::string base_joint;  // name of the free base's joint (URDF or SRDF virtual joint), or ""
  // What the loader accepted but is worth saying ("FILE:LINE: ..."; e.g. a mimic joint of an
  // unknown master, which then moves on its own): printed as warnings, errors with --strict.
  std::vector<std::string> warnings;
};

// Number of independent movable joints = size of q.
inline int num_dofs(const Robot& robot) { return static_cast<int>(robot.dof_joints.size()); }

// Index of the link / joint / chain with this name; throws std::invalid_argument listing the
// robot's source file when it does not exist.
int FindLink(const Robot& robot, const std::string& name);
int FindJoint(const Robot& robot, const std::string& name);
int FindChain(const Robot& robot, const std::string& name);

// Names of the independent movable joints in q order.
std::vector<std::string> DofNames(const Robot& robot);

// Lower / upper limits of q (size num_dofs; ±∞ for continuous joints).
Eigen::VectorXd LowerLimits(const Robot& robot);
Eigen::VectorXd UpperLimits(const Robot& robot);

// Holds the dofs `frozen` (indices into q) at their values in `q` (size num_dofs): each joint
// driving one of them, mimic joints included, becomes a fixed joint whose origin includes its
// motion at that value (origin · Rot(axis, v) or origin · Trans(axis · v)); the other dofs keep
// their order and are renumbered. Returns, for each dof of the new robot, its index in the old q.
// Throws std::invalid_argument for an index out of range or a q of the wrong size.
std::vector<int> FreezeDofs(const std::vector<int>& frozen, const Eigen::VectorXd& q, Robot* robot);

// True if links a and b are rigidly attached (only fixed joints between them) or are parent and
// child bodies: bodies are links merged across fixed joints, and bodies without collision geometry
// (e.g. the massless frame between the two axes of a 2-DOF joint) are skipped when looking for the
// parent. Self-collision checks skip such pairs. O(links · depth); call it at set-up time.
bool AreAdjacent(const Robot& robot, int link_a, int link_b);

}  // namespace planning
