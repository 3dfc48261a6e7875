// Lookups and small queries on the immutable Robot.
#include "planning/robot/robot.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace planning {
namespace {

template <typename T>
int FindByName(const std::vector<T>& items, const std::string& name, const char* what,
               const Robot& robot) {
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == name) return static_cast<int>(i);
  }
  std::string known;
  for (size_t i = 0; i < items.size() && i < 40; ++i) known += (i ? ", " : "") + items[i].name;
  throw std::invalid_argument(robot.source + ": no " + what + " named '" + name +
                              "' (known: " + known + ")");
}

// The link that carries `link` rigidly: walk up through fixed joints.
int RigidBodyRoot(const Robot& robot, int link) {
  while (true) {
    const int j = robot.links[link].parent_joint;
    if (j < 0 || robot.joints[j].type != JointType::kFixed) return link;
    link = robot.joints[j].parent_link;
  }
}

// True if any link rigidly attached to body root `body` has collision geometry.
bool BodyHasCollision(const Robot& robot, int body) {
  for (size_t l = 0; l < robot.links.size(); ++l) {
    if (!robot.links[l].collisions.empty() && RigidBodyRoot(robot, static_cast<int>(l)) == body) {
      return true;
    }
  }
  return false;
}

// The nearest ancestor body of `body` (a rigid-body root) that has collision geometry, skipping
// massless frames such as the intermediate link of a 2-DOF joint; −1 if none.
int CollisionParentBody(const Robot& robot, int body) {
  while (true) {
    const int j = robot.links[body].parent_joint;
    if (j < 0) return -1;
    body = RigidBodyRoot(robot, robot.joints[j].parent_link);
    if (BodyHasCollision(robot, body)) return body;
  }
}

}  // namespace

int FindLink(const Robot& robot, const std::string& name) {
  return FindByName(robot.links, name, "link", robot);
}
int FindJoint(const Robot& robot, const std::string& name) {
  return FindByName(robot.joints, name, "joint", robot);
}
int FindChain(const Robot& robot, const std::string& name) {
  return FindByName(robot.chains, name, "chain", robot);
}

std::vector<std::string> DofNames(const Robot& robot) {
  std::vector<std::string> names;
  names.reserve(robot.dof_joints.size());
  for (int j : robot.dof_joints) names.push_back(robot.joints[j].name);
  return names;
}

Eigen::VectorXd LowerLimits(const Robot& robot) {
  Eigen::VectorXd lo(num_dofs(robot));
  for (int k = 0; k < num_dofs(robot); ++k) lo[k] = robot.joints[robot.dof_joints[k]].limits.lower;
  return lo;
}

Eigen::VectorXd UpperLimits(const Robot& robot) {
  Eigen::VectorXd hi(num_dofs(robot));
  for (int k = 0; k < num_dofs(robot); ++k) hi[k] = robot.joints[robot.dof_joints[k]].limits.upper;
  return hi;
}

std::vector<int> FreezeDofs(const std::vector<int>& frozen, const Eigen::VectorXd& q,
                            Robot* robot) {
  const int n = num_dofs(*robot);
  if (q.size() != n) {
    throw std::invalid_argument("FreezeDofs: q has " + std::to_string(q.size()) +
                                " values, the robot " + std::to_string(n) + " dofs");
  }
  std::vector<bool> is_frozen(n, false);
  for (int k : frozen) {
    if (k < 0 || k >= n) throw std::invalid_argument("FreezeDofs: dof index out of range");
    is_frozen[k] = true;
  }
  std::vector<int> new_index(n, -1), kept;
  for (int k = 0; k < n; ++k) {
    if (is_frozen[k]) continue;
    new_index[k] = static_cast<int>(kept.size());
    kept.push_back(k);
  }
  for (Joint& j : robot->joints) {
    if (j.dof < 0) continue;
    if (!is_frozen[j.dof]) {
      j.dof = new_index[j.dof];
      continue;
    }
    const double v = j.is_mimic ? j.mimic_multiplier * q[j.dof] + j.mimic_offset : q[j.dof];
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    if (j.type == JointType::kPrismatic) {
      motion.translation() = j.axis * v;
    } else if (j.type != JointType::kFixed) {
      motion.linear() = Eigen::AngleAxisd(v, j.axis).toRotationMatrix();
    }
    j.parent_from_joint = j.parent_from_joint * motion;
    j.type = JointType::kFixed;
    j.dof = -1;
    j.is_mimic = false;
  }
  std::vector<int> dof_joints;
  for (int k : kept) dof_joints.push_back(robot->dof_joints[k]);
  robot->dof_joints = std::move(dof_joints);
  return kept;
}

bool AreAdjacent(const Robot& robot, int link_a, int link_b) {
  const int a = RigidBodyRoot(robot, link_a);
  const int b = RigidBodyRoot(robot, link_b);
  if (a == b) return true;
  return CollisionParentBody(robot, a) == b || CollisionParentBody(robot, b) == a;
}

}  // namespace planning
