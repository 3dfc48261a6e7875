// Forward kinematics and Jacobians: one pass over the links in topological order.
#include "planning/robot/kinematics.h"

#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

namespace planning {
namespace {

void CheckLinkIndex(const Robot& robot, int link, const char* fn) {
  if (link < 0 || link >= static_cast<int>(robot.links.size())) {
    throw std::invalid_argument(std::string(fn) + ": link index " + std::to_string(link) +
                                " out of range [0, " + std::to_string(robot.links.size()) + ")");
  }
}

void CheckSize(const Eigen::Ref<Eigen::MatrixXd>& m, Eigen::Index rows, Eigen::Index cols,
               const char* fn) {
  if (m.rows() != rows || m.cols() != cols) {
    throw std::invalid_argument(std::string(fn) + ": output is " + std::to_string(m.rows()) + "x" +
                                std::to_string(m.cols()) + ", expected " + std::to_string(rows) +
                                "x" + std::to_string(cols));
  }
}

// Calls visit(joint, j, m) for every movable joint j on the path link→root (m: its mimic
// multiplier, or 1).
template <typename Visit>
void ForEachJointToRoot(const Robot& robot, int link, Visit&& visit) {
  for (int l = link; l >= 0;) {
    const int j = robot.links[l].parent_joint;
    if (j < 0) break;
    const Joint& joint = robot.joints[j];
    if (joint.dof >= 0) visit(joint, j, joint.is_mimic ? joint.mimic_multiplier : 1.0);
    l = joint.parent_link;
  }
}

// Adds the contribution of every movable joint on the path root→link to the 3×n position
// Jacobian of world point p (and, if J_ang is non-null, to the 3×n angular Jacobian).
template <typename Lin, typename Ang>
void AccumulateJacobian(const Robot& robot, const KinematicsData& kin, int link,
                        const Eigen::Vector3d& p, Lin&& J_lin, Ang* J_ang) {
  ForEachJointToRoot(robot, link, [&](const Joint& joint, int j, double m) {
    const Eigen::Vector3d& a = kin.joint_axis_world[j];
    if (joint.type == JointType::kPrismatic) {
      J_lin.col(joint.dof) += m * a;
    } else {
      J_lin.col(joint.dof) += m * a.cross(p - kin.joint_origin_world[j]);
      if (J_ang) J_ang->col(joint.dof) += m * a;
    }
  });
}

}  // namespace

KinematicsData::KinematicsData(const Robot& robot)
    : q(Eigen::VectorXd::Zero(num_dofs(robot))),
      joint_value(robot.joints.size(), 0.0),
      world_from_link(robot.links.size(), Eigen::Isometry3d::Identity()),
      joint_axis_world(robot.joints.size(), Eigen::Vector3d::UnitX()),
      joint_origin_world(robot.joints.size(), Eigen::Vector3d::Zero()) {}

void ForwardKinematics(const Robot& robot, const Eigen::VectorXd& q, KinematicsData* kin) {
  const int n = num_dofs(robot);
  if (q.size() != n) {
    throw std::invalid_argument("ForwardKinematics: q has " + std::to_string(q.size()) +
                                " entries, robot '" + robot.name + "' has " + std::to_string(n) +
                                " degrees of freedom");
  }
  for (int k = 0; k < n; ++k) {
    if (!std::isfinite(q[k])) {
      throw std::invalid_argument("ForwardKinematics: q[" + std::to_string(k) + "] (" +
                                  robot.joints[robot.dof_joints[k]].name + ") is not finite");
    }
  }
  assert(kin->world_from_link.size() == robot.links.size());
  kin->q = q;
  kin->world_from_link[0] = robot.world_from_root;
  // Links are topologically sorted, so each parent pose is final before its children are visited.
  for (size_t l = 1; l < robot.links.size(); ++l) {
    const int j = robot.links[l].parent_joint;
    const Joint& joint = robot.joints[j];
    const Eigen::Isometry3d world_from_joint =
        kin->world_from_link[joint.parent_link] * joint.parent_from_joint;
    double v = 0.0;
    if (joint.dof >= 0)
      v = joint.is_mimic ? joint.mimic_multiplier * q[joint.dof] + joint.mimic_offset
                         : q[joint.dof];
    kin->joint_value[j] = v;
    kin->joint_origin_world[j] = world_from_joint.translation();
    kin->joint_axis_world[j] = world_from_joint.linear() * joint.axis;
    Eigen::Isometry3d& out = kin->world_from_link[l];
    out = world_from_joint;
    switch (joint.type) {
      case JointType::kRevolute:
      case JointType::kContinuous:
        out.linear() =
            world_from_joint.linear() * Eigen::AngleAxisd(v, joint.axis).toRotationMatrix();
        break;
      case JointType::kPrismatic:
        out.translation() += kin->joint_axis_world[j] * v;
        break;
      case JointType::kFixed:
        break;
    }
  }
}

void PointJacobian(const Robot& robot, const KinematicsData& kin, int link,
                   const Eigen::Vector3d& p_link, Eigen::Ref<Eigen::MatrixXd> J) {
  CheckLinkIndex(robot, link, "PointJacobian");
  CheckSize(J, 3, num_dofs(robot), "PointJacobian");
  J.setZero();
  const Eigen::Vector3d p = kin.world_from_link[link] * p_link;
  AccumulateJacobian(robot, kin, link, p, J, static_cast<Eigen::Ref<Eigen::MatrixXd>*>(nullptr));
}

void AddPointJacobianAlong(const Robot& robot, const KinematicsData& kin, int link,
                           const Eigen::Vector3d& p_world, const Eigen::Vector3d& u, double scale,
                           Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> row) {
  CheckLinkIndex(robot, link, "AddPointJacobianAlong");
  if (row.size() != num_dofs(robot)) {
    throw std::invalid_argument("AddPointJacobianAlong: row has " + std::to_string(row.size()) +
                                " entries, expected " + std::to_string(num_dofs(robot)));
  }
  ForEachJointToRoot(robot, link, [&](const Joint& joint, int j, double mimic) {
    const double m = scale * mimic;
    const Eigen::Vector3d& a = kin.joint_axis_world[j];
    if (joint.type == JointType::kPrismatic) {
      row[joint.dof] += m * a.dot(u);
    } else {
      row[joint.dof] += m * a.dot((p_world - kin.joint_origin_world[j]).cross(u));
    }
  });
}

void FrameJacobian(const Robot& robot, const KinematicsData& kin, int link,
                   Eigen::Ref<Eigen::MatrixXd> J) {
  CheckLinkIndex(robot, link, "FrameJacobian");
  CheckSize(J, 6, num_dofs(robot), "FrameJacobian");
  J.setZero();
  auto lin = J.topRows<3>();
  auto ang = J.bottomRows<3>();
  AccumulateJacobian(robot, kin, link, kin.world_from_link[link].translation(), lin, &ang);
}

int ChainSize(const Robot& robot, int chain) {
  if (chain < 0 || chain >= static_cast<int>(robot.chains.size())) {
    throw std::invalid_argument("chain index " + std::to_string(chain) + " out of range");
  }
  const ChainSpec& c = robot.chains[chain];
  return static_cast<int>(c.point_link.size()) + (c.closed ? 1 : 0);
}

void ChainPoints(const Robot& robot, const KinematicsData& kin, int chain, Eigen::Matrix3Xd* P) {
  const int size = ChainSize(robot, chain);
  const ChainSpec& c = robot.chains[chain];
  if (P->cols() != size) P->resize(3, size);
  const int n = static_cast<int>(c.point_link.size());
  for (int k = 0; k < size; ++k) {
    const int src = k % n;
    P->col(k) = kin.world_from_link[c.point_link[src]] * c.point_local.col(src);
  }
}

void ChainJacobian(const Robot& robot, const KinematicsData& kin, int chain,
                   Eigen::Ref<Eigen::MatrixXd> dP) {
  const int size = ChainSize(robot, chain);
  CheckSize(dP, 3 * size, num_dofs(robot), "ChainJacobian");
  const ChainSpec& c = robot.chains[chain];
  const int n = static_cast<int>(c.point_link.size());
  dP.setZero();
  for (int k = 0; k < size; ++k) {
    const int src = k % n;
    const int link = c.point_link[src];
    const Eigen::Vector3d p = kin.world_from_link[link] * c.point_local.col(src);
    AccumulateJacobian(robot, kin, link, p, dP.middleRows<3>(3 * k),
                       static_cast<Eigen::Ref<Eigen::MatrixXd>*>(nullptr));
  }
}

}  // namespace planning
