// Lookups and small queries on the immutable Robot.
#include "planning/robot/robot.h"

#include <stdexcept>

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

bool AreAdjacent(const Robot& robot, int link_a, int link_b) {
  const int a = RigidBodyRoot(robot, link_a);
  const int b = RigidBodyRoot(robot, link_b);
  if (a == b) return true;
  return CollisionParentBody(robot, a) == b || CollisionParentBody(robot, b) == a;
}

}  // namespace planning
