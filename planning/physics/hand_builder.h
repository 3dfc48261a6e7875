// Building the ODE descriptions (SimHand, SimObject) from planning's robot model and grasp
// objects, following the closing protocol of docs/methods.md §10.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <utility>
#include <vector>

#include "planning/grasp_object.h"
#include "planning/physics/grasp_simulation.h"
#include "planning/robot.h"

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
  double default_torque = 2.0;  // used when the URDF gives no effort limit [N m]
};

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
