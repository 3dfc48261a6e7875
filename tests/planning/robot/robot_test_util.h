// Shared helpers for the robot / kinematics / collision tests: asset paths and seeded random q.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <string>

#include "planning/robot/robot.h"

namespace planning {

inline std::string AssetFile(const std::string& rel) {
  return std::string(TOPOPLAN_SOURCE_DIR) + "/assets/" + rel;
}

inline std::string TestDataFile(const std::string& rel) {
  return std::string(TOPOPLAN_SOURCE_DIR) + "/tests/planning/data/" + rel;
}

// Uniform q inside the joint limits (continuous / unbounded joints in [−π, π], prismatic in
// [−1, 1] when unbounded).
inline Eigen::VectorXd RandomQ(const Robot& robot, std::mt19937* rng) {
  Eigen::VectorXd q(num_dofs(robot));
  for (int k = 0; k < num_dofs(robot); ++k) {
    const JointLimits& l = robot.joints[robot.dof_joints[k]].limits;
    const double lo = std::max(l.lower, -3.14159), hi = std::min(l.upper, 3.14159);
    q[k] = std::uniform_real_distribution<double>(lo, hi)(*rng);
  }
  return q;
}

}  // namespace planning
