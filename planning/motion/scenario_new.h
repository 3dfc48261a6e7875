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
//            movable joints: the link where the tree branches into fingers (subtrees reaching
//            less than max(0.2 m, ¼ of the path walked from the root)) or the leaf at the end (a
//            flange); at a branch into longer subtrees, the one with the most joints; when that finds no arm (the tree branches first: a humanoid, a
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
// "unwrap" (internal/scenario_unwrap.h): the arm starts hooked around a pole and must unwrap
//   chain    "arm": for each link from the first arm joint to the hand, its origin and the centre
//            of its collision geometry: segments run through the arm's body, so the chain crosses
//            the pole's axis only where the arm would hit the pole (link origins alone leave
//            segments in free space at offset joints; a tool point between gripper fingers would
//            straddle the pole).
//   samples  1500 seeded configurations of the arm joints inside their limits (revolute 0.1 rad
//            in), the rest at the default pose; kept if every chain point is 5 cm above the
//            floor (the lowest link origin in the default pose) and there is no self-collision.
//   start    per sample, the line along the normal of the chain's best-fit plane through the
//            point of a 9 × 9 grid in that plane with the largest |winding| (topology/winding.h)
//            among points 0.1 m from every chain segment; samples by decreasing |winding| ≥ 0.15
//            turns: the first whose pole (--object, default assets/objects/pole.urdf, chain
//            "axis", centred on that point) touches nothing and whose total writhe arm × pole is
//            at least 0.15 in modulus, and for which a goal exists.
//   goal     the sample nearest the start (joint space) with |total writhe| < 0.02, |winding| <
//            0.05, every chain segment 0.1 m off the pole's axis and no collision; its tool
//            point is the reach target; written as final_pose.init.
//   tasks    those of assets/scenarios/unwrap.json (writhe → 0, collision, off the pole's line,
//            winding guard, joint limits, reach); success: writhe below 0.05, the tool within
//            0.05 m of the target, winding continuous (no tunnelling) and below 0.1 at the end.
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
  std::string task = "ring";  // "ring", "reach" or "unwrap"
  // The ring URDF (chain "loop"; empty: assets/objects/ring.urdf), or for "unwrap" the pole URDF
  // (chain "axis"; empty: assets/objects/pole.urdf).
  std::string object;
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
  Eigen::Vector3d ring_center = Eigen::Vector3d::Zero();  // world, m: ring or pole centre
  Eigen::VectorXd goal_q;                                 // the IK goal, q order
  // The start (q order): "ring", the hand in front of the ring by IK; "unwrap", the hook; empty:
  // the default pose.
  Eigen::VectorXd start_q;
  std::vector<std::string> notes;  // what was chosen and why (printed by the command)
};

NewScenario MakeNewScenario(const std::string& urdf, const NewScenarioOptions& options);

}  // namespace planning
