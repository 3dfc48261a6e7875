// Forward kinematics, point / frame Jacobians and chain points with their Jacobians.
//
// Usage: size a KinematicsData once per robot (and per thread / time step), then per step call
//   ForwardKinematics(robot, q, &kin);            // fills world_from_link for configuration q
//   PointJacobian(robot, kin, link, p_link, J);   // any number of Jacobian queries at that q
// None of the per-step functions allocate once their outputs have the right size.
//
// Frames: the world frame is the root link frame (links[0]). All Jacobians are expressed in the
// world frame and differentiate with respect to q (size n = num_dofs(robot), see robot.h for the
// order). Revolute / continuous columns are in m/rad (linear) and 1 (angular); prismatic columns
// are unitless (linear) and 0 (angular). Mimic joints add multiplier × their column to the
// master's column.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "planning/robot/robot.h"

namespace planning {

// Per-configuration workspace. Sized once from the robot; reused for every q.
struct KinematicsData {
  explicit KinematicsData(const Robot& robot);

  Eigen::VectorXd q;                                // the last configuration (size n)
  std::vector<double> joint_value;                  // per joint: angle/displacement (0 if fixed)
  std::vector<Eigen::Isometry3d> world_from_link;   // per link
  std::vector<Eigen::Vector3d> joint_axis_world;    // per joint: unit axis in the world frame
  std::vector<Eigen::Vector3d> joint_origin_world;  // per joint: joint frame origin, world frame
};

// Computes, for every link i, world_from_link[i] = Π over the path root→i of
//   parent_from_joint · Rot(axis, v) (revolute/continuous) or · Trans(v·axis) (prismatic),
// with v = q[dof] (independent) or multiplier·q[dof] + offset (mimic). Also stores every joint's
// value, world axis and world origin. Throws std::invalid_argument if q.size() != num_dofs or q
// has a non-finite entry. O(links), no allocation.
void ForwardKinematics(const Robot& robot, const Eigen::VectorXd& q, KinematicsData* kin);

// Position Jacobian of a point fixed to `link`: p_world = world_from_link[link] · p_link, and
// J = ∂p_world/∂q (3 × n, world frame). Column k sums over the joints on the path root→link that
// are driven by q[k]: m·(a × (p_world − o)) for revolute joints, m·a for prismatic ones (a = world
// axis, o = world joint origin, m = mimic multiplier or 1). Requires ForwardKinematics first.
// Throws std::invalid_argument if J is not 3 × n or link is out of range. O(depth · 3).
void PointJacobian(const Robot& robot, const KinematicsData& kin, int link,
                   const Eigen::Vector3d& p_link, Eigen::Ref<Eigen::MatrixXd> J);

// Directional derivative of a world point moving with `link`: row += scale · uᵀ ∂p_world/∂q
// (1 × n, any stride: e.g. a row of a Jacobian), without forming the 3 × n Jacobian; column k gets
// m·a·((p_world − o) × u) for revolute joints and m·a·u for prismatic ones (PointJacobian's
// notation). Requires ForwardKinematics first. Throws std::invalid_argument if row is not 1 × n or
// link is out of range. O(depth).
void AddPointJacobianAlong(const Robot& robot, const KinematicsData& kin, int link,
                           const Eigen::Vector3d& p_world, const Eigen::Vector3d& u, double scale,
                           Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> row);

// Geometric frame Jacobian of `link` (6 × n, world frame): rows 0–2 = ∂(link origin)/∂q (linear
// velocity of the origin per unit q̇), rows 3–5 = angular velocity ω per unit q̇ (a for revolute
// joints, 0 for prismatic). Requires ForwardKinematics first. Throws std::invalid_argument if J
// is not 6 × n.
void FrameJacobian(const Robot& robot, const KinematicsData& kin, int link,
                   Eigen::Ref<Eigen::MatrixXd> J);

// Number of points ChainPoints returns for robot.chains[chain]: N, or N + 1 when the chain is
// closed (point 0 repeated at the end).
int ChainSize(const Robot& robot, int chain);

// World positions of the chain's points: P is 3 × ChainSize (resized if needed), column k =
// world_from_link[point_link[k]] · point_local[:, k]. Requires ForwardKinematics first.
void ChainPoints(const Robot& robot, const KinematicsData& kin, int chain, Eigen::Matrix3Xd* P);

// Jacobian of the chain points: dP is (3·ChainSize) × n, rows 3k..3k+2 = ∂p_k/∂q (the layout of
// topology::ChainWritheJacobian's da_dq). Throws std::invalid_argument if dP has another size.
void ChainJacobian(const Robot& robot, const KinematicsData& kin, int chain,
                   Eigen::Ref<Eigen::MatrixXd> dP);

}  // namespace planning
