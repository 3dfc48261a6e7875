// GraspSimulation (planning/physics/grasp_simulation.h): building the ODE world from a
// description, stepping it, and saving/restoring its state. The checks and masses of a description
// are in grasp_simulation_description.cc, the per-step work of GraspSimulation::Impl in
// grasp_simulation_world.cc.
#include "planning/physics/grasp_simulation.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "planning/physics/internal/grasp_simulation_impl.h"
#include "planning/physics/internal/ode_convert.h"

namespace planning::physics {

using internal::kPi;
using internal::SetBodyPose;

double SoftFingerSpinArm(double mu, double patch_radius) {
  if (!(mu >= 0) || !std::isfinite(mu) || !(patch_radius >= 0) || !std::isfinite(patch_radius)) {
    throw std::invalid_argument("SoftFingerSpinArm: mu and the patch radius must be finite, >= 0");
  }
  return 3.0 * kPi / 16.0 * mu * patch_radius;
}

// --- Construction -------------------------------------------------------------------------------

void GraspSimulation::Impl::BuildWorld() {
  world = dWorldCreate();
  dWorldSetGravity(world, 0, 0, 0);
  dWorldSetERP(world, options.erp);
  dWorldSetCFM(world, options.cfm);
  dWorldSetContactSurfaceLayer(world, options.surface_layer);
  dWorldSetContactMaxCorrectingVel(world, options.max_correcting_velocity);
  dWorldSetQuickStepNumIterations(world, options.quickstep_iterations);
  dWorldSetAutoDisableFlag(world, 0);
  contact_group = dJointGroupCreate(0);
}

void GraspSimulation::Impl::BuildHandLinks() {
  const int n = static_cast<int>(hand.links.size());
  link_body.resize(n);
  link_com.resize(n);
  hinge.assign(n, nullptr);
  lo_stop.assign(n, 0.0);
  hi_stop.assign(n, 0.0);
  axis_inertia.assign(n, 0.0);
  q_target.resize(n);
  kin_pose.resize(n);
  for (int i = 0; i < n; ++i) {
    const SimHandLink& l = hand.links[i];  // the copy: trimesh storage must outlive geoms
    Eigen::Vector3d com;
    dMass mass = internal::CentredMass(l.shapes, l.mass, &com);
    link_com[i] = com;
    q_target[i] = i == 0 ? 0.0 : l.q_target;
    dBodyID body = dBodyCreate(world);
    dBodySetMass(body, &mass);
    Eigen::Isometry3d body_pose = l.world_from_link;
    body_pose.translate(com);
    SetBodyPose(body, body_pose);
    if (i == 0 || options.hand_mode == HandMode::kKinematic) dBodySetKinematic(body);
    link_body[i] = body;
    for (const SimShape& s : l.shapes) {
      dGeomID g = MakeGeom(s);
      Attach(g, body, s.body_from_shape, com);
      hand_geom.push_back(g);
      hand_geom_link.push_back(i);
    }
  }
}

void GraspSimulation::Impl::BuildHinges() {
  const int n = static_cast<int>(hand.links.size());
  for (int i = 1; i < n; ++i) {
    const SimHandLink& l = hand.links[i];
    dJointID j = dJointCreateHinge(world, nullptr);
    // Body 1 = child, body 2 = parent: the hinge angle is the child's rotation relative to the
    // parent about the axis, zero at the start configuration.
    dJointAttach(j, link_body[i], link_body[l.parent]);
    dJointSetHingeAnchor(j, l.joint_anchor.x(), l.joint_anchor.y(), l.joint_anchor.z());
    const Eigen::Vector3d a = l.joint_axis.normalized();
    dJointSetHingeAxis(j, a.x(), a.y(), a.z());
    lo_stop[i] = std::max(l.lower - l.q_start, -kPi + 1e-3);
    hi_stop[i] = std::min(l.upper - l.q_start, kPi - 1e-3);
    dJointSetHingeParam(j, dParamLoStop, lo_stop[i]);
    dJointSetHingeParam(j, dParamHiStop, hi_stop[i]);
    axis_inertia[i] = internal::AxisInertia(link_body[i], l.joint_anchor, a);
    dJointSetHingeParam(j, dParamStopERP, 0.2);
    dJointSetHingeParam(j, dParamStopCFM, 1e-5);
    dJointSetHingeParam(j, dParamFMax, l.max_torque);
    dJointSetHingeParam(j, dParamVel, 0.0);
    hinge[i] = j;
  }
}

void GraspSimulation::Impl::BuildObject(const SimObject& source) {
  object = source;
  dMass mass = internal::CentredMass(source.shapes, source.mass, &object_com);
  object_body = dBodyCreate(world);
  dBodySetMass(object_body, &mass);
  Eigen::Isometry3d body_pose = source.world_from_object;
  body_pose.translate(object_com);
  SetBodyPose(object_body, body_pose);
  for (const SimShape& s : object.shapes) {
    dGeomID g = MakeGeom(s);
    Attach(g, object_body, s.body_from_shape, object_com);
    object_geom.push_back(g);
  }
}

GraspSimulation::GraspSimulation(const OdeRuntime& /*runtime*/, const SimHand& hand,
                                 const SimObject& object, const SimOptions& options)
    : impl_(std::make_unique<Impl>()) {
  internal::Validate(hand, object, options);
  Impl& m = *impl_;
  m.hand = hand;
  m.options = options;
  const int n = static_cast<int>(hand.links.size());
  m.BuildWorld();
  // Hand links: bodies with the centre of mass at the body origin; geoms attached with offsets.
  m.BuildHandLinks();
  if (options.hand_mode == HandMode::kMotorized) m.BuildHinges();
  // Object: one free body at its centre of mass.
  m.BuildObject(object);
  state_.world_from_link.resize(n);
  state_.joint_angles.assign(n, 0.0);
  state_.contacts.reserve(64);
  // Initial state: poses and the contacts of the start configuration (no constraint created).
  if (options.hand_mode == HandMode::kKinematic) m.PlaceKinematic(0.0);
  m.Collide(false, &state_);
  m.ReadState(&state_);
}

GraspSimulation::~GraspSimulation() = default;

int GraspSimulation::num_links() const { return static_cast<int>(impl_->hand.links.size()); }

void GraspSimulation::SetGravity(const Eigen::Vector3d& g) {
  if (!g.allFinite()) throw std::invalid_argument("SetGravity: non-finite gravity");
  dWorldSetGravity(impl_->world, g.x(), g.y(), g.z());
}

void GraspSimulation::SetJointTargets(const std::vector<double>& q_target) {
  if (q_target.size() != impl_->hand.links.size()) {
    throw std::invalid_argument("SetJointTargets: expected " +
                                std::to_string(impl_->hand.links.size()) + " values, got " +
                                std::to_string(q_target.size()));
  }
  for (size_t i = 1; i < q_target.size(); ++i) {
    const SimHandLink& l = impl_->hand.links[i];
    if (!std::isfinite(q_target[i])) throw std::invalid_argument("SetJointTargets: non-finite");
    impl_->q_target[i] = std::clamp(q_target[i], l.lower, l.upper);
  }
}

// --- Stepping -----------------------------------------------------------------------------------

void GraspSimulation::Step() {
  Impl& m = *impl_;
  if (state_.blown_up) return;
  // QuickStep shuffles constraint rows with ODE's global generator: reseed it from the step index
  // so results do not depend on other simulations or on earlier runs in the process.
  dRandSetSeed(static_cast<unsigned long>(state_.step) * 2654435761ul + 12345ul);
  if (m.options.hand_mode == HandMode::kKinematic) {
    m.PlaceKinematic(state_.time);
  } else {
    m.ApplyMotors();
  }
  m.Collide(true, &state_);
  if (m.options.stepper == Stepper::kWorldStep) {
    dWorldStep(m.world, m.options.dt);
  } else {
    dWorldQuickStep(m.world, m.options.dt);
  }
  dJointGroupEmpty(m.contact_group);
  state_.step += 1;
  state_.time = state_.step * m.options.dt;
  m.ReadState(&state_);
}

// Snapshot layout per body (links, then the object): position (3), quaternion (4), linear (3)
// and angular (3) velocity; then the joint targets.
SimSnapshot GraspSimulation::SaveState() const {
  const Impl& m = *impl_;
  SimSnapshot snap;
  snap.time = state_.time;
  snap.step = state_.step;
  auto save = [&](dBodyID b) {
    const dReal* p = dBodyGetPosition(b);
    const dReal* q = dBodyGetQuaternion(b);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* w = dBodyGetAngularVel(b);
    snap.data.insert(snap.data.end(), {p[0], p[1], p[2], q[0], q[1], q[2], q[3], v[0], v[1], v[2],
                                       w[0], w[1], w[2]});
  };
  for (dBodyID b : m.link_body) save(b);
  save(m.object_body);
  snap.data.insert(snap.data.end(), m.q_target.begin(), m.q_target.end());
  return snap;
}

void GraspSimulation::RestoreState(const SimSnapshot& snap) {
  Impl& m = *impl_;
  const size_t bodies = m.link_body.size() + 1;
  if (snap.data.size() != 13 * bodies + m.q_target.size()) {
    throw std::invalid_argument("RestoreState: snapshot from a different simulation");
  }
  const double* d = snap.data.data();
  auto restore = [&](dBodyID b) {
    dBodySetPosition(b, d[0], d[1], d[2]);
    const dQuaternion q = {d[3], d[4], d[5], d[6]};
    dBodySetQuaternion(b, q);
    dBodySetLinearVel(b, d[7], d[8], d[9]);
    dBodySetAngularVel(b, d[10], d[11], d[12]);
    d += 13;
  };
  for (dBodyID b : m.link_body) restore(b);
  restore(m.object_body);
  std::copy(d, d + m.q_target.size(), m.q_target.begin());
  state_.time = snap.time;
  state_.step = snap.step;
  state_.blown_up = false;
  state_.blowup_reason.clear();
  m.Collide(false, &state_);
  m.ReadState(&state_);
}

}  // namespace planning::physics
