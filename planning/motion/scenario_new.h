// A working scenario for any robot the tool loads (`topoplan scenario new`): the hand found in the
// kinematic tree, the ring (or a reach target) placed in reach, the goal pose found by inverse
// kinematics (planning/robot/ik.h), a box and the success criteria written out.
//
//   NewScenarioOptions o;                       // task "ring" (default) or "reach"
//   const NewScenario s = MakeNewScenario("robots/arm.urdf", o);
//   WriteFileAtomic("arm_ring.json", s.json.dump(2));
//
// How the pieces are chosen (each written into the file with a "//" comment key where a user is
// expected to edit):
//   hand     --hand LINK; else walking down from the root while exactly one child subtree has
//            movable joints: the link where the tree branches (a palm with fingers) or the leaf at
//            the end (a flange); when that finds no arm (the tree branches first: a humanoid, a
//            mobile manipulator), the parent link of the SRDF's first end_effector that is not a
//            foot or leg. Joints off the path root → hand (the other arm, legs) are frozen too.
//            The arm is the path root → hand; the joints below the hand (fingers) are frozen at
//            the start values ("frozen_joints").
//   tool     a point on the hand, L ahead of its origin along the approach axis (from the last
//            arm joint to the hand, or to the centroid of the hand's subtree), L = the hand's
//            size, at least 0.05 m.
//   chain    "hand": the origins of the last three arm links, the hand and the tool point.
//   start    "ring": the hand in front of the ring on its axis (tool 0.1 m + 0.6 × its length
//            before the ring's plane), by IK from the goal, collision-free and not yet through;
//            "reach" (or when that fails): the SRDF's first group_state, else zeros moved into
//            the limits (DefaultQ).
//   ring     assets/objects/ring.urdf (or --object), its axis along the base's +x, in front of the
//            first arm joint: candidates at 35–65 % of the arm's reach and three heights, the
//            first where IK puts the tool through the ring, collision-free, with the hand chain
//            through the loop (ChainSegmentThroughLoop) and a start in front of it (above) that
//            does not touch the ring; else the first with such a goal (start: the default pose).
//   tasks    collision margin 0.02 m (wider margins keep the cost of closely packed links of
//            real arms active everywhere); joint limits 0.05 rad / 0.002 m.
//   goal     IK (multistart, seeded) of the tool point beyond the ring with the approach axis
//            along +x; written as final_pose.init.
//   box      around the goal tool point; success: inside_box and through_loop.
// Throws std::invalid_argument for a robot without an arm (the root branches at once, no movable
// joint) and when no candidate works (the message says what was tried).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace planning {

struct NewScenarioOptions {
  std::string task = "ring";               // "ring" or "reach"
  std::string object;                      // ring URDF; empty: assets/objects/ring.urdf
  std::vector<std::string> package_paths;  // package:// roots for the robot
  std::string srdf;                        // empty: FindSrdf
  // The hand link (the arm is the path root → hand); empty: found (see the file comment).
  std::string hand;
  std::uint32_t seed = 0;  // IK random starts
  std::string name;        // scenario name; empty: ROBOT_TASK
};

struct NewScenario {
  nlohmann::ordered_json json;  // the scenario file
  std::string hand_link;
  Eigen::Vector3d tool_target = Eigen::Vector3d::Zero();  // world, m
  Eigen::Vector3d ring_center = Eigen::Vector3d::Zero();  // world, m ("ring" only)
  Eigen::VectorXd goal_q;                                 // the IK goal, q order
  // The start (q order): "ring", the hand in front of the ring by IK; empty: the default pose.
  Eigen::VectorXd start_q;
  std::vector<std::string> notes;  // what was chosen and why (printed by the command)
};

NewScenario MakeNewScenario(const std::string& urdf, const NewScenarioOptions& options);

}  // namespace planning
