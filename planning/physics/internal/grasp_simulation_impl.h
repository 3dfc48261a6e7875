// Private: the ODE side of GraspSimulation (planning/physics/grasp_simulation.h) — the checks and
// mass properties of a description (grasp_simulation_description.cc) and GraspSimulation::Impl,
// built in grasp_simulation.cc and advanced by its per-step methods in grasp_simulation_world.cc.
#pragma once

#include <ode/ode.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "planning/physics/grasp_simulation.h"

namespace planning::physics {
namespace internal {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr int kMaxContactsPerPair = 16;  // upper bound of SimOptions::max_contacts_per_pair

// Throws std::invalid_argument naming the link or shape for an inconsistent description (see the
// GraspSimulation constructor) or options outside their ranges.
void Validate(const SimHand& hand, const SimObject& object, const SimOptions& o);

// Total mass of the shapes (uniform density, spread by volume) scaled to `total` [kg]; returns
// the centre of mass (body frame) in *com and the mass re-centred on it (ODE requires the centre
// of mass at the body origin). No shapes, or shapes of zero volume: a sphere of radius 1 cm.
dMass CentredMass(const std::vector<SimShape>& shapes, double total, Eigen::Vector3d* com);

// Inertia of a body about the axis through `anchor` along the unit vector `axis` (world frame,
// current pose) [kg m²]: aᵀ R I_c Rᵀ a + m |(c − anchor) × a|².
double AxisInertia(dBodyID body, const Eigen::Vector3d& anchor, const Eigen::Vector3d& axis);

}  // namespace internal

struct GraspSimulation::Impl {
  SimHand hand;
  SimOptions options;
  dWorldID world = nullptr;
  dJointGroupID contact_group = nullptr;
  std::vector<dBodyID> link_body;         // per link
  std::vector<Eigen::Vector3d> link_com;  // link-frame centre of mass = body origin
  std::vector<dJointID> hinge;            // per link (null for the palm / kinematic mode)
  std::vector<dGeomID> hand_geom;
  std::vector<int> hand_geom_link;
  std::vector<dTriMeshDataID> mesh_data;
  SimObject object;  // copy: trimesh vertex storage must outlive the geoms
  std::vector<dGeomID> object_geom;
  dBodyID object_body = nullptr;
  Eigen::Vector3d object_com = Eigen::Vector3d::Zero();  // object frame
  std::vector<double> q_target;
  // Per link with a hinge: stops relative to q_start and the link's inertia about the hinge
  // axis through the anchor [kg m²] (SimHand::limit_stop_torque).
  std::vector<double> lo_stop, hi_stop, axis_inertia;
  std::vector<Eigen::Isometry3d> kin_pose;  // kinematic mode scratch
  dContact contact_buffer[internal::kMaxContactsPerPair];

  ~Impl();

  // --- Construction (grasp_simulation.cc), in this order after `hand` and `options` are set.
  // The world (zero gravity, options' ERP/CFM/contact parameters, no auto-disable) and the
  // contact joint group.
  void BuildWorld();
  // Per hand link: a body with its centre of mass at the body origin (kinematic for the palm and
  // in kKinematic mode) and its shapes' geoms; sizes the per-link vectors.
  void BuildHandLinks();
  // kMotorized: a hinge per link i > 0 (body 1 = link, body 2 = parent; angle 0 at q_start) with
  // its stops, motor torque limit and axis inertia.
  void BuildHinges();
  // The object: a copy of `source` (its trimesh storage must outlive the geoms) as one free body
  // at its centre of mass.
  void BuildObject(const SimObject& source);

  // --- Per step (grasp_simulation_world.cc).
  // An ODE geom for a shape (not yet attached); trimesh data is kept in mesh_data.
  dGeomID MakeGeom(const SimShape& s);
  // Attaches `geom` to `body` with the shape's pose relative to the body origin (= com).
  static void Attach(dGeomID geom, dBodyID body, const Eigen::Isometry3d& frame_from_shape,
                     const Eigen::Vector3d& com);
  // World pose of link i's frame / the object frame (body poses shifted back by the com).
  Eigen::Isometry3d LinkPose(int i) const;
  Eigen::Isometry3d ObjectPose() const;
  // Kinematic forward kinematics from the start configuration at time t (the joint angles
  // interpolated from q_start to q_target over options.kinematic_close_time):
  // T_i(q) = T_parent(q) · T_parent_start⁻¹ · Rot(anchor, axis, q_i − q_start,i) · T_i,start.
  void KinematicPoses(double t, std::vector<Eigen::Isometry3d>* poses) const;
  // Kinematic mode: puts every link exactly at its scheduled pose for time t and gives it the
  // velocity that reaches the pose of t + dt (ODE integrates kinematic bodies with it).
  void PlaceKinematic(double t);
  // Motorized mode: velocity command of the position loop, torque-limited by the motor.
  void ApplyMotors();
  // Hand–object narrow phase. Fills state->contacts; with create_joints also adds one contact
  // joint per point (Coulomb pyramid via dContactApprox1, soft ERP/CFM).
  void Collide(bool create_joints, SimState* state);
  // Reads poses, joint angles and velocities, and checks for a numerical blow-up.
  void ReadState(SimState* state) const;
  // Kinematic mode: link i's scheduled joint angle at time t.
  double ScheduledAngle(int i, double t) const;
};

}  // namespace planning::physics
