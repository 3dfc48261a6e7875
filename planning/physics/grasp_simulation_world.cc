// GraspSimulation::Impl's per-step work (planning/physics/internal/grasp_simulation_impl.h): ODE
// geoms, link and object poses, the kinematic schedule, the hinge motors, the hand–object contacts
// and the read-back of the state with its blow-up check.
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "planning/physics/grasp_simulation.h"

#include "base/numbers.h"
#include "planning/physics/internal/grasp_simulation_impl.h"
#include "planning/physics/internal/ode_convert.h"

namespace planning::physics {

using internal::BodyPose;
using internal::SetBodyPose;
using internal::ToOdeMatrix;
using internal::Vec;

GraspSimulation::Impl::~Impl() {
  for (dGeomID g : hand_geom) dGeomDestroy(g);
  for (dGeomID g : object_geom) dGeomDestroy(g);
  for (dTriMeshDataID d : mesh_data) dGeomTriMeshDataDestroy(d);
  if (contact_group) dJointGroupDestroy(contact_group);
  if (world) dWorldDestroy(world);
}

dGeomID GraspSimulation::Impl::MakeGeom(const SimShape& s) {
  switch (s.kind) {
    case SimShape::Kind::kSphere:
      return dCreateSphere(nullptr, s.size.x());
    case SimShape::Kind::kCapsule:
      return dCreateCapsule(nullptr, s.size.x(), s.size.y());
    case SimShape::Kind::kCylinder:
      return dCreateCylinder(nullptr, s.size.x(), s.size.y());
    case SimShape::Kind::kBox:
      return dCreateBox(nullptr, s.size.x(), s.size.y(), s.size.z());
    case SimShape::Kind::kTrimesh: {
      dTriMeshDataID data = dGeomTriMeshDataCreate();
      mesh_data.push_back(data);
      // The Eigen storage outlives the geom: it is owned by `hand`/the object copy below.
      dGeomTriMeshDataBuildDouble(data, s.vertices.data(), 3 * sizeof(double),
                                  static_cast<int>(s.vertices.cols()), s.triangles.data(),
                                  static_cast<int>(3 * s.triangles.cols()), 3 * sizeof(int));
      return dCreateTriMesh(nullptr, data, nullptr, nullptr, nullptr);
    }
  }
  return nullptr;
}

void GraspSimulation::Impl::Attach(dGeomID geom, dBodyID body,
                                   const Eigen::Isometry3d& frame_from_shape,
                                   const Eigen::Vector3d& com) {
  dGeomSetBody(geom, body);
  const Eigen::Vector3d t = frame_from_shape.translation() - com;
  dGeomSetOffsetPosition(geom, t.x(), t.y(), t.z());
  dMatrix3 r;
  ToOdeMatrix(frame_from_shape.linear(), r);
  dGeomSetOffsetRotation(geom, r);
}

Eigen::Isometry3d GraspSimulation::Impl::LinkPose(int i) const {
  Eigen::Isometry3d pose = BodyPose(link_body[i]);
  pose.translate(-link_com[i]);
  return pose;
}

Eigen::Isometry3d GraspSimulation::Impl::ObjectPose() const {
  Eigen::Isometry3d pose = BodyPose(object_body);
  pose.translate(-object_com);
  return pose;
}

void GraspSimulation::Impl::KinematicPoses(double t, std::vector<Eigen::Isometry3d>* poses) const {
  const double s = options.kinematic_close_time > 0
                       ? std::clamp(t / options.kinematic_close_time, 0.0, 1.0)
                       : 1.0;
  (*poses)[0] = hand.links[0].world_from_link;
  for (size_t i = 1; i < hand.links.size(); ++i) {
    const SimHandLink& l = hand.links[i];
    const double q = l.q_start + s * (q_target[i] - l.q_start);
    const Eigen::Vector3d axis = l.joint_axis.normalized();
    Eigen::Isometry3d rot = Eigen::Isometry3d::Identity();
    rot.translate(l.joint_anchor);
    rot.rotate(Eigen::AngleAxisd(q - l.q_start, axis));
    rot.translate(-l.joint_anchor);
    const SimHandLink& p = hand.links[l.parent];
    (*poses)[i] = (*poses)[l.parent] * p.world_from_link.inverse() * rot * l.world_from_link;
  }
}

void GraspSimulation::Impl::PlaceKinematic(double t) {
  KinematicPoses(t, &kin_pose);
  std::vector<Eigen::Isometry3d>& now = kin_pose;
  for (size_t i = 1; i < hand.links.size(); ++i) {
    Eigen::Isometry3d body_now = now[i];
    body_now.translate(link_com[i]);
    SetBodyPose(link_body[i], body_now);
  }
  KinematicPoses(t + options.dt, &kin_pose);
  for (size_t i = 1; i < hand.links.size(); ++i) {
    Eigen::Isometry3d body_next = kin_pose[i];
    body_next.translate(link_com[i]);
    const Eigen::Isometry3d body_now = BodyPose(link_body[i]);
    const Eigen::Vector3d v = (body_next.translation() - body_now.translation()) / options.dt;
    const Eigen::AngleAxisd d(body_next.linear() * body_now.linear().transpose());
    const Eigen::Vector3d w = d.axis() * (d.angle() / options.dt);
    dBodySetLinearVel(link_body[i], v.x(), v.y(), v.z());
    dBodySetAngularVel(link_body[i], w.x(), w.y(), w.z());
  }
}

void GraspSimulation::Impl::ApplyMotors() {
  for (size_t i = 1; i < hand.links.size(); ++i) {
    const double q = hand.links[i].q_start + dJointGetHingeAngle(hinge[i]);
    const double v = std::clamp(options.motor_gain * (q_target[i] - q), -options.max_joint_speed,
                                options.max_joint_speed);
    dJointSetHingeParam(hinge[i], dParamVel, v);
    if (hand.limit_stop_torque) {
      // ODE applies fudge × max_torque open-loop when the motor pushes away from a stop.
      const double a = q - hand.links[i].q_start;
      const bool away = (a <= lo_stop[i] && v > 0) || (a >= hi_stop[i] && v < 0);
      double fudge = 1.0;
      if (away) {
        const double needed =
            axis_inertia[i] * std::abs(v - dJointGetHingeAngleRate(hinge[i])) / options.dt;
        fudge = std::min(1.0, needed / std::max(hand.links[i].max_torque, 1e-12));
      }
      dJointSetHingeParam(hinge[i], dParamFudgeFactor, fudge);
    }
  }
}

void GraspSimulation::Impl::Collide(bool create_joints, SimState* state) {
  state->contacts.clear();
  state->max_depth = 0.0;
  unsigned long long touched = 0;  // bit per link (links beyond 64 are counted separately)
  int num_touched_high = 0;
  std::vector<char> touched_high;
  int mode = dContactSoftERP | dContactSoftCFM;
  if (options.friction_pyramid) mode |= dContactApprox1;  // includes dContactApprox1_N
  // Soft finger: spinning friction only (rows for rolling about t1, t2 are dropped by passing
  // a negative rho, rho2; with dContactAxisDep = dContactMu2 the second direction uses mu2).
  const double spin_arm = SoftFingerSpinArm(options.mu, options.contact_patch_radius);
  if (spin_arm > 0) mode |= dContactRolling | dContactAxisDep;
  for (size_t gi = 0; gi < hand_geom.size(); ++gi) {
    dReal ha[6];
    dGeomGetAABB(hand_geom[gi], ha);
    for (dGeomID og : object_geom) {
      dReal oa[6];
      dGeomGetAABB(og, oa);
      if (ha[0] > oa[1] || oa[0] > ha[1] || ha[2] > oa[3] || oa[2] > ha[3] || ha[4] > oa[5] ||
          oa[4] > ha[5]) {
        continue;
      }
      const int n = dCollide(hand_geom[gi], og, options.max_contacts_per_pair,
                             &contact_buffer[0].geom, sizeof(dContact));
      const int link = hand_geom_link[gi];
      for (int k = 0; k < n; ++k) {
        dContact& c = contact_buffer[k];
        SimContact sc;
        sc.position = Vec(c.geom.pos);
        sc.normal = Vec(c.geom.normal);
        sc.depth = c.geom.depth;
        sc.link = link;
        state->contacts.push_back(sc);
        state->max_depth = std::max(state->max_depth, sc.depth);
        if (link < 64) {
          touched |= 1ull << link;
        } else {
          if (touched_high.empty()) touched_high.assign(hand.links.size(), 0);
          if (!touched_high[link]) ++num_touched_high;
          touched_high[link] = 1;
        }
        if (!create_joints) continue;
        c.surface.mode = mode;
        c.surface.mu = options.mu;
        c.surface.soft_erp = options.contact_erp;
        c.surface.soft_cfm = options.contact_cfm;
        c.surface.mu2 = options.mu;
        c.surface.rho = -1.0;
        c.surface.rho2 = -1.0;
        c.surface.rhoN = spin_arm;
        c.surface.bounce = 0.0;
        dJointID j = dJointCreateContact(world, contact_group, &c);
        dJointAttach(j, link_body[link], object_body);
      }
    }
  }
  state->num_contact_links = __builtin_popcountll(touched) + num_touched_high;
}

void GraspSimulation::Impl::ReadState(SimState* state) const {
  for (size_t i = 0; i < hand.links.size(); ++i) {
    state->world_from_link[i] = LinkPose(static_cast<int>(i));
    if (i == 0) continue;
    state->joint_angles[i] = hinge[i] ? hand.links[i].q_start + dJointGetHingeAngle(hinge[i])
                                      : ScheduledAngle(static_cast<int>(i), state->time);
  }
  state->world_from_object = ObjectPose();
  state->object_linear_velocity = Vec(dBodyGetLinearVel(object_body));
  state->object_angular_velocity = Vec(dBodyGetAngularVel(object_body));
  // Blow-up: any non-finite number, or a body moving implausibly fast.
  auto check = [&](dBodyID b, int link) {
    if (state->blown_up) return;
    const Eigen::Vector3d p = Vec(dBodyGetPosition(b));
    const Eigen::Vector3d v = Vec(dBodyGetLinearVel(b));
    const Eigen::Vector3d w = Vec(dBodyGetAngularVel(b));
    std::string reason;
    if (!p.allFinite() || !v.allFinite() || !w.allFinite()) {
      reason = "non-finite state";
    } else if (v.norm() > options.blowup_linear_speed) {
      reason = "speed " + base::FormatShortest(v.norm()) + " m/s";
    } else if (w.norm() > options.blowup_angular_speed) {
      reason = "angular speed " + base::FormatShortest(w.norm()) + " rad/s";
    } else {
      return;
    }
    state->blown_up = true;
    state->blowup_reason =
        (link < 0 ? std::string("object") : "hand link '" + hand.links[link].name + "'") + ": " +
        reason;
  };
  check(object_body, -1);
  for (size_t i = 1; i < hand.links.size(); ++i) check(link_body[i], static_cast<int>(i));
  if (state->blown_up) {
    state->blowup_reason += " at t = " + base::FormatShortest(state->time) + " s";
  }
}

double GraspSimulation::Impl::ScheduledAngle(int i, double t) const {
  const double s = options.kinematic_close_time > 0
                       ? std::clamp(t / options.kinematic_close_time, 0.0, 1.0)
                       : 1.0;
  return hand.links[i].q_start + s * (q_target[i] - hand.links[i].q_start);
}

}  // namespace planning::physics
