// Private: the arm of `scenario new` (planning/motion/scenario_new.h): which link is the hand and
// which joints move the arm.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "planning/collision/collision.h"
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

// A robot chain as scenario files write it: (link, point in the link's frame, m) per point.
using LinkPoints = std::vector<std::pair<int, Eigen::Vector3d>>;

// The world positions of `points` in `kin` (3 × N).
Eigen::Matrix3Xd WorldPoints(const LinkPoints& points, const KinematicsData& kin);

// What every task of `scenario new` starts from: the start pose, the arm, its tool point and size.
struct ArmSetup {
  Eigen::VectorXd q0;            // DefaultQ moved into the limits (size n)
  bool start_moved = false;      // q0 differs from DefaultQ
  Eigen::VectorXd lower, upper;  // the joint limits (size n)
  Arm arm;
  std::vector<int> arm_links;  // links on the path whose parent joint moves, root first
  // In q0: the hand's approach axis (world, unit), the tool point in the hand frame (m), the
  // hand's size L ≥ 0.05 m (tool = hand origin + L·approach), the first arm joint's origin.
  Eigen::Vector3d approach = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d tool_local = Eigen::Vector3d::Zero();
  Eigen::Vector3d shoulder = Eigen::Vector3d::Zero();
  double hand_size = 0.05;
  double reach = 0.0;  // Σ distances between consecutive arm joints + to the hand + L, m
  // The scene's collision options with the link pairs that touch in q0 disabled (`touching`).
  CollisionOptions collision_options;
  std::vector<std::pair<std::string, std::string>> touching;
};

// The arm set-up of `scene` for hand link `hand` (empty: ChooseArm finds it); appends what was
// chosen to `notes`. Throws std::invalid_argument as ChooseArm does.
ArmSetup SetUpArm(const RobotScene& scene, const std::string& hand,
                  std::vector<std::string>* notes);

// True when every revolute arm joint of q (size n) lies min(0.1, ¼ range) rad inside its limits
// (a planner's soft limit terms need room); prismatic and non-arm joints are not held to it.
bool AwayFromLimits(const Robot& robot, const ArmSetup& setup, const Eigen::VectorXd& q);

}  // namespace planning::internal
