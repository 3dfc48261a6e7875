// ODE simulation of a hand holding an object, advanced one time step at a time.
//
// The description is plain data (no robot model, no files): a hand is a tree of rigid links
// joined by hinges, rooted at a palm that is welded to the world; an object is one free rigid body
// made of primitive shapes. The hand is either joint-position controlled through hinge velocity
// motors with torque limits (kMotorized, the default: fingers close until the motors saturate on
// the object) or kinematic (kKinematic: every link follows the forward kinematics of joint angles
// interpolated from the start to the target configuration, with infinite stiffness).
//
// Frames: everything is given and reported in the world frame; the palm (link 0) stays where it
// is. Units SI (m, kg, s, rad, N).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "planning/physics/ode_runtime.h"

namespace planning::physics {

// A collision/inertia primitive rigidly attached to a body, in that body's frame.
struct SimShape {
  enum class Kind { kSphere, kCapsule, kBox, kCylinder, kTrimesh };
  Kind kind = Kind::kSphere;
  // kSphere: (radius, −, −). kCapsule, kCylinder: (radius, length, −) with the axis along the
  // shape's local z and `length` the cylindrical part (a capsule adds two hemispherical caps).
  // kBox: full side lengths (x, y, z). kTrimesh: unused.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d body_from_shape = Eigen::Isometry3d::Identity();
  // kTrimesh only: vertices (3×V, shape frame) and counter-clockwise triangles (3×F indices).
  Eigen::Matrix3Xd vertices;
  Eigen::Matrix3Xi triangles;
};

// Volume of a primitive shape [m³]: sphere 4/3·πr³, capsule πr²l + 4/3·πr³, cylinder πr²l, box
// x·y·z; 0 for a trimesh.
double PrimitiveVolume(const SimShape& s);

// One link of the hand. Link 0 is the palm: parent −1, no joint, never moves. Every other link
// has a parent with a smaller index and a hinge joint to it.
struct SimHandLink {
  std::string name;
  int parent = -1;
  // Pose of the link in the world at the start configuration (q = q_start for every joint).
  Eigen::Isometry3d world_from_link = Eigen::Isometry3d::Identity();
  // Hinge: anchor point and unit axis in the world frame at the start configuration. Positive
  // angles rotate the link about `joint_axis` (right-hand rule) relative to its parent.
  Eigen::Vector3d joint_anchor = Eigen::Vector3d::Zero();
  Eigen::Vector3d joint_axis = Eigen::Vector3d::UnitX();
  double q_start = 0.0;   // joint angle at the start configuration [rad]
  double q_target = 0.0;  // angle the controller drives to [rad]
  double lower = -3.0;  // joint limits [rad], lower ≤ q_start, q_target ≤ upper, inside (−π, π)
  double upper = 3.0;
  double max_torque = 2.0;  // motor torque limit [N m] (kMotorized)
  double mass = 0.05;       // [kg], spread over the shapes by volume
  std::vector<SimShape> shapes;
};

// The hand: links[0] is the palm. Contacts are only generated between hand and object (links of
// the hand never collide with each other).
struct SimHand {
  std::vector<SimHandLink> links;
  // Motor torque at a joint stop (kMotorized). ODE drives a powered hinge that sits at one of its
  // stops with an open-loop torque of max_torque (its "fudge factor" 1) whenever the commanded
  // velocity points away from the stop, however small the velocity error. On a light link that
  // torque changes the joint speed by max_torque·dt / I per step (I = the link's inertia about
  // the hinge axis): ≈ 5 N m · 1 ms / 2e-6 kg m² = 2500 rad/s for a human finger phalanx, which
  // throws the finger off in one step. With `limit_stop_torque` the torque at a stop is limited
  // to I·|v_cmd − q̇| / dt, what brings the joint to its commanded speed v_cmd in one step (the
  // fudge factor set per step to that torque / max_torque, at most 1). Off by default: the SDH
  // results and golden images were produced with ODE's plain behaviour.
  bool limit_stop_torque = false;
};

// The object: one free rigid body. `world_from_object` places the object frame; the shapes are
// given in that frame. Mass is spread over the shapes by volume (uniform density); the centre of
// mass and inertia follow from the shapes.
struct SimObject {
  std::vector<SimShape> shapes;
  double mass = 0.1;
  Eigen::Isometry3d world_from_object = Eigen::Isometry3d::Identity();
};

// The object's mass properties as the simulation gives them to ODE (see SimObject): mass [kg],
// centre of mass in the object frame [m], inertia about the centre of mass in object-frame axes
// [kg m²].
struct ObjectMass {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};
ObjectMass ObjectMassProperties(const SimObject& object);

enum class HandMode { kMotorized, kKinematic };
enum class Stepper { kWorldStep, kQuickStep };
inline constexpr base::EnumName<Stepper> kStepperNames[] = {
    {Stepper::kWorldStep, "world_step"},
    {Stepper::kQuickStep, "quick_step"},
};
constexpr std::span<const base::EnumName<Stepper>> EnumNames(Stepper) { return kStepperNames; }

// Solver and contact parameters (docs/methods.md §10).
struct SimOptions {
  double dt = 1e-3;  // step [s]
  HandMode hand_mode = HandMode::kMotorized;
  // Constraint solver, the same for every hand and object. kWorldStep (dWorldStep): ODE's exact
  // LCP solver (Dantzig pivoting on the full constraint system). kQuickStep (dWorldQuickStep):
  // `quickstep_iterations` projected Gauss-Seidel sweeps, which do not converge the soft-finger
  // torsional rows: a 50 g plate pinched by two fingertips turns 49° about the contact line with
  // 60 iterations, 8.7° with 100, 2.2° with 200, 0.8° with 400, 0.0° with kWorldStep
  // (tests/planning/physics/grasp_simulation_test.cc). For the SDH and the human hand it is cheaper
  // in total (48 trials at μ = 1: 34 s of simulation, QuickStep 60: 41 s), but its cost grows with
  // the cube of the rows: the test claw (16 links, ~20 contacts) takes 12 s per stability test,
  // not 1.4 s.
  Stepper stepper = Stepper::kWorldStep;
  int quickstep_iterations = 60;  // kQuickStep only: Gauss-Seidel sweeps per step
  // Coulomb friction coefficient. With `friction_pyramid` (dContactApprox1) the friction bound is
  // mu × normal force; without it ODE treats mu as a force bound in newtons.
  double mu = 1.0;
  bool friction_pyramid = true;
  // Soft-finger contact (docs/methods.md §10): radius a [m] of the contact patch every hand–object
  // contact is taken to have. A patch resists spinning about the contact normal up to
  // |τ_n| ≤ SoftFingerSpinArm(mu, a) · f_n (ODE spinning friction rhoN with dContactApprox1_N,
  // proportional to the contact's normal force; no rolling resistance). 0 = point contacts, which
  // resist no torque about their normal. The same for every hand and object. Needs the exact
  // solver (kWorldStep, the default) to hold: see `stepper`.
  double contact_patch_radius = 0.005;
  double erp = 0.2;                      // global error reduction
  double cfm = 1e-5;                     // global constraint force mixing
  double contact_erp = 0.2;              // per-contact soft ERP
  double contact_cfm = 1e-4;             // per-contact soft CFM
  double surface_layer = 1e-3;           // allowed penetration [m]
  double max_correcting_velocity = 0.2;  // [m/s]
  int max_contacts_per_pair = 4;
  // Motor position loop: v = clamp(gain (q_target − q), ±max_joint_speed), force ≤ max_torque.
  double motor_gain = 15.0;           // [1/s]
  double max_joint_speed = 1.4;       // [rad/s]
  double kinematic_close_time = 0.4;  // kKinematic: time to go from q_start to q_target [s]
  // Blow-up detection: any non-finite state or a body faster than these.
  double blowup_linear_speed = 50.0;    // [m/s]
  double blowup_angular_speed = 500.0;  // [rad/s]
};

// Torsional friction arm of a soft finger [m]: the largest torque about the contact normal per
// unit normal force of a circular patch of radius a with a Hertzian pressure distribution
// p(r) ∝ √(1 − r²/a²) and Coulomb friction mu, ∫ mu p r dA / ∫ p dA = (3π/16) mu a ≈ 0.59 mu a
// (Howe & Cutkosky 1996; a uniform pressure would give (2/3) mu a). 0 for a = 0 or mu = 0.
// Throws std::invalid_argument for a negative or non-finite mu or a.
double SoftFingerSpinArm(double mu, double patch_radius);

// One hand–object contact point of the last step (world frame).
struct SimContact {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // from the object towards the hand link
  double depth = 0.0;                                // penetration [m]
  int link = -1;                                     // hand link index
};

// Everything a viewer or a frame writer needs after a step.
struct SimState {
  double time = 0.0;
  int step = 0;
  std::vector<Eigen::Isometry3d> world_from_link;  // one per hand link
  std::vector<double> joint_angles;                // one per link (0 for the palm)
  Eigen::Isometry3d world_from_object = Eigen::Isometry3d::Identity();
  Eigen::Vector3d object_linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d object_angular_velocity = Eigen::Vector3d::Zero();
  std::vector<SimContact> contacts;
  int num_contact_links = 0;  // distinct hand links touching the object
  double max_depth = 0.0;     // deepest contact [m]
  bool blown_up = false;      // numerical failure detected; Step() then does nothing
  std::string blowup_reason;
};

// Saved dynamic state (body poses and velocities, time, kinematic schedule) for RestoreState.
struct SimSnapshot {
  double time = 0.0;
  int step = 0;
  std::vector<double> data;
};

// The simulation: built once from a description, then advanced with Step(). Deterministic: the
// same description and options give bit-identical states step by step. Not copyable.
class GraspSimulation {
 public:
  // Builds the ODE world. Throws std::invalid_argument for an inconsistent description (palm not
  // first, parent ≥ own index, non-finite numbers, non-positive mass or sizes, limits outside
  // (−π, π), empty object) naming the link or shape.
  GraspSimulation(const OdeRuntime& runtime, const SimHand& hand, const SimObject& object,
                  const SimOptions& options);
  ~GraspSimulation();
  GraspSimulation(const GraspSimulation&) = delete;
  GraspSimulation& operator=(const GraspSimulation&) = delete;

  // World-frame gravity vector [m/s²] (zero at construction).
  void SetGravity(const Eigen::Vector3d& gravity);
  // Replaces the joint targets (size = links, entry 0 ignored).
  void SetJointTargets(const std::vector<double>& q_target);

  // Advances one step of options.dt: hand control, collision, constraint solve, blow-up check.
  // After a blow-up the state is frozen and state().blown_up is true.
  void Step();

  const SimState& state() const { return state_; }
  SimSnapshot SaveState() const;
  void RestoreState(const SimSnapshot& snapshot);

  // Number of hand links (including the palm).
  int num_links() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  SimState state_;
};

}  // namespace planning::physics
