// Building the ODE descriptions (SimHand, SimObject) from planning's robot model and grasp
// objects, following the closing protocol of docs/methods.md §10.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <utility>
#include <vector>

#include "planning/grasp/grasp_object.h"
#include "planning/physics/grasp_simulation.h"
#include "planning/robot/robot.h"

namespace planning::physics {

struct HandBuildOptions {
  // Flexion joints start opened by open_by and are driven to their grasp value + close_by, so
  // the torque-limited motors press the fingers onto the object (rad).
  double open_by = 0.1;
  double close_by = 0.15;
  // Joints whose name contains one of these are held at their grasp value instead (the SDH's
  // coupled spread axis).
  std::vector<std::string> hold_joints = {"knuckle"};
  // Link masses by name substring (first match), else default_mass [kg]. SDH values from the
  // public Schunk SDH URDF.
  std::vector<std::pair<std::string, double>> link_masses = {
      {"palm", 1.0288}, {"knuckle", 0.047}, {"proximal", 0.167}, {"distal", 0.0929}};
  double default_mass = 0.05;
  // > 0: a link that no link_masses entry matches weighs density × the volume of its collision
  // shapes (uniform density; links without collision shapes get default_mass) [kg/m³].
  double density = 0.0;
  double default_torque = 2.0;  // used when the URDF gives no effort limit [N m]
  // Motor torque limits by joint name substring (first match), overriding the URDF effort [N m].
  std::vector<std::pair<std::string, double>> joint_torques;
  bool limit_stop_torque = false;  // SimHand::limit_stop_torque
  // Held joints become rigid (their link is merged into the parent body) instead of hinges whose
  // motors hold the grasp value. Removes the light, shapeless intermediate body of a two-axis
  // joint (the human MCP: abduction, then flexion about the same point), which the iterative
  // solver cannot keep in place against a heavy object.
  bool weld_held_joints = false;
};

// Options for the human hand (assets/robots/human_hand.urdf, palm link "hand_palm"): the MCP and
// CMC abduction joints ("_abd") are held at their grasp value and welded (weld_held_joints), the
// links weigh 1100 kg/m³ (tissue) × their capsule volume (≈ 15, 8 and 4 g for the index
// phalanges; shapeless links 5 g), the motors keep the URDF efforts (5 N m) and the torque at a
// joint stop is limited (limit_stop_torque). Flexion joints open and close as for the SDH.
HandBuildOptions HumanHandBuildOptions();

// The hand below `palm_link` at configuration q (world frame from ForwardKinematics): the palm
// becomes link 0 (welded), every revolute joint a motorised hinge, fixed joints are merged into
// their parent body, collision geometry becomes SimShapes (meshes are skipped). Throws
// std::invalid_argument for a wrong-sized q or an unknown palm link.
SimHand BuildSimHand(const Robot& robot, const Eigen::VectorXd& q, const std::string& palm_link,
                     const HandBuildOptions& options = {});

// Name of the hand-model link each SimHand link came from (same order as BuildSimHand's links).
std::vector<std::string> SimHandLinkNames(const SimHand& hand);

// A grasp object as an ODE body: primitives map one to one; a torus (arc) becomes a ring of
// `torus_segments` capsules (ODE has no torus).
SimObject BuildSimObject(const GraspObject& object, const Eigen::Isometry3d& world_from_object,
                         int torus_segments = 16);

}  // namespace planning::physics
