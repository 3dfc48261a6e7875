// Private: the arm of `scenario new` (planning/motion/scenario_new.h): which link is the hand and
// which joints move the arm.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "planning/motion/robot_scene.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"

namespace planning::internal {

// The arm: links root → hand, and the hand.
struct Arm {
  std::vector<int> path;  // link indices, root first, hand last
  int hand = 0;
  std::vector<int> arm_dofs, other_dofs;    // q indices on the path root → hand, and the rest
  std::vector<std::string> branch_choices;  // "parent → child" where FindArm chose a subtree
};

// World position of `link`'s frame.
inline Eigen::Vector3d Origin(const KinematicsData& kin, int link) {
  return kin.world_from_link[link].translation();
}

// The arm: to `hand` when given (FindLink's error for an unknown name); else walking down from the
// root (scenario_new.h "hand"); where that finds no arm or had to choose between long subtrees,
// the parent link of the SRDF's first end_effector that is not a foot or leg. Appends what chose
// the hand to `notes`. Throws std::invalid_argument when no arm of 2 or more joints is found.
Arm ChooseArm(const RobotScene& scene, const std::string& hand, std::vector<std::string>* notes);

// The links of the subtree below `link` (itself excluded).
std::vector<int> Subtree(const Robot& robot, int link);

}  // namespace planning::internal
