#include "planning/physics/grasp_simulation.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace planning::physics {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxContactsPerPair = 16;

// --- Conversions between Eigen and ODE ---------------------------------------------------------

Eigen::Isometry3d BodyPose(dBodyID body) {
  const dReal* p = dBodyGetPosition(body);
  const dReal* q = dBodyGetQuaternion(body);  // (w, x, y, z)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return pose;
}

void SetBodyPose(dBodyID body, const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
  dBodySetQuaternion(body, dq);
  const Eigen::Vector3d& t = pose.translation();
  dBodySetPosition(body, t.x(), t.y(), t.z());
}

void ToOdeMatrix(const Eigen::Matrix3d& r, dMatrix3 out) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out[4 * i + j] = r(i, j);
    out[4 * i + 3] = 0;
  }
}

Eigen::Vector3d Vec(const dReal* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

bool Finite(const Eigen::Isometry3d& t) { return t.matrix().allFinite(); }

// --- Validation
// -----------------------------------------------------------------------------------

void CheckShape(const SimShape& s, const std::string& where) {
  if (!s.size.allFinite() || !Finite(s.body_from_shape)) {
    throw std::invalid_argument(where + ": non-finite size or pose");
  }
  switch (s.kind) {
    case SimShape::Kind::kSphere:
      if (s.size.x() <= 0) throw std::invalid_argument(where + ": sphere radius must be > 0");
      break;
    case SimShape::Kind::kCapsule:
    case SimShape::Kind::kCylinder:
      if (s.size.x() <= 0 || s.size.y() < 0) {
        throw std::invalid_argument(where + ": radius must be > 0 and length >= 0");
      }
      break;
    case SimShape::Kind::kBox:
      if ((s.size.array() <= 0).any()) {
        throw std::invalid_argument(where + ": box sides must be > 0");
      }
      break;
    case SimShape::Kind::kTrimesh:
      if (s.vertices.cols() < 4 || s.triangles.cols() < 4 || !s.vertices.allFinite() ||
          s.triangles.minCoeff() < 0 || s.triangles.maxCoeff() >= s.vertices.cols()) {
        throw std::invalid_argument(where +
                                    ": trimesh needs >= 4 finite vertices and >= 4 "
                                    "triangles with valid indices");
      }
      break;
  }
}

void Validate(const SimHand& hand, const SimObject& object, const SimOptions& o) {
  if (hand.links.empty()) throw std::invalid_argument("hand: no links (link 0 must be the palm)");
  if (hand.links[0].parent != -1) throw std::invalid_argument("hand: link 0 must have parent -1");
  for (size_t i = 0; i < hand.links.size(); ++i) {
    const SimHandLink& l = hand.links[i];
    const std::string where = "hand link " + std::to_string(i) + " '" + l.name + "'";
    if (i > 0 && (l.parent < 0 || l.parent >= static_cast<int>(i))) {
      throw std::invalid_argument(where + ": parent must be in [0, " + std::to_string(i) + ")");
    }
    if (!Finite(l.world_from_link) || !l.joint_anchor.allFinite() || !l.joint_axis.allFinite() ||
        !std::isfinite(l.q_start) || !std::isfinite(l.q_target) || !std::isfinite(l.mass) ||
        !std::isfinite(l.max_torque)) {
      throw std::invalid_argument(where + ": non-finite value");
    }
    // Masses beyond 1e6 kg overflow ODE's mass matrices (its error handler fires mid-step).
    if (l.mass <= 0 || l.mass > 1e6)
      throw std::invalid_argument(where + ": mass must be in (0, 1e6] kg");
    if (i > 0) {
      if (l.joint_axis.norm() < 1e-9) throw std::invalid_argument(where + ": zero joint axis");
      if (!(l.lower > -kPi && l.upper < kPi && l.lower <= l.upper)) {
        throw std::invalid_argument(where +
                                    ": joint limits must satisfy -pi < lower <= upper < pi");
      }
    }
    for (size_t k = 0; k < l.shapes.size(); ++k) {
      CheckShape(l.shapes[k], where + " shape " + std::to_string(k));
    }
  }
  if (object.shapes.empty()) throw std::invalid_argument("object: no shapes");
  if (!(object.mass > 0 && object.mass <= 1e6)) {
    throw std::invalid_argument("object: mass must be in (0, 1e6] kg");
  }
  if (!Finite(object.world_from_object)) throw std::invalid_argument("object: non-finite pose");
  for (size_t k = 0; k < object.shapes.size(); ++k) {
    CheckShape(object.shapes[k], "object shape " + std::to_string(k));
  }
  if (!(o.contact_patch_radius >= 0) || !std::isfinite(o.contact_patch_radius)) {
    throw std::invalid_argument("simulation options: contact_patch_radius must be finite and >= 0");
  }
  if (!(o.dt > 0) || !(o.mu >= 0) || !std::isfinite(o.mu) || o.max_contacts_per_pair < 1 ||
      o.max_contacts_per_pair > kMaxContactsPerPair || o.quickstep_iterations < 1) {
    throw std::invalid_argument(
        "simulation options: need dt > 0, finite mu >= 0, 1 <= "
        "max_contacts_per_pair <= 16, quickstep_iterations >= 1");
  }
}

// Mass of one shape with unit density, placed at its pose in the body frame.
dMass ShapeMass(const SimShape& s) {
  dMass m;
  switch (s.kind) {
    case SimShape::Kind::kSphere:
      dMassSetSphere(&m, 1.0, s.size.x());
      break;
    case SimShape::Kind::kCapsule:
      dMassSetCapsule(&m, 1.0, 3, s.size.x(), std::max(s.size.y(), 1e-9));
      break;
    case SimShape::Kind::kCylinder:
      dMassSetCylinder(&m, 1.0, 3, s.size.x(), std::max(s.size.y(), 1e-9));
      break;
    case SimShape::Kind::kBox:
      dMassSetBox(&m, 1.0, s.size.x(), s.size.y(), s.size.z());
      break;
    case SimShape::Kind::kTrimesh: {
      // Inertia of the bounding box: good enough for a rigid object's mass distribution.
      const Eigen::Vector3d lo = s.vertices.rowwise().minCoeff();
      const Eigen::Vector3d hi = s.vertices.rowwise().maxCoeff();
      const Eigen::Vector3d ext = (hi - lo).cwiseMax(1e-6);
      dMassSetBox(&m, 1.0, ext.x(), ext.y(), ext.z());
      const Eigen::Vector3d c = 0.5 * (lo + hi);
      dMassTranslate(&m, c.x(), c.y(), c.z());
      break;
    }
  }
  dMatrix3 r;
  ToOdeMatrix(s.body_from_shape.linear(), r);
  dMassRotate(&m, r);
  const Eigen::Vector3d& t = s.body_from_shape.translation();
  dMassTranslate(&m, t.x(), t.y(), t.z());
  return m;
}

// Total mass of the shapes scaled to `total`; returns the centre of mass (body frame) in *com and
// the mass re-centred on it (ODE requires the centre of mass at the body origin).
dMass CentredMass(const std::vector<SimShape>& shapes, double total, Eigen::Vector3d* com) {
  dMass sum;
  dMassSetZero(&sum);
  for (const SimShape& s : shapes) {
    dMass m = ShapeMass(s);
    dMassAdd(&sum, &m);
  }
  if (shapes.empty() || !(sum.mass > 0)) {
    dMassSetSphereTotal(&sum, total, 0.01);
  }
  dMassAdjust(&sum, total);
  *com = Eigen::Vector3d(sum.c[0], sum.c[1], sum.c[2]);
  dMassTranslate(&sum, -com->x(), -com->y(), -com->z());
  return sum;
}

// Inertia of a body about the axis through `anchor` along the unit vector `axis` (world frame,
// current pose) [kg m²]: aᵀ R I_c Rᵀ a + m |(c − anchor) × a|².
double AxisInertia(dBodyID body, const Eigen::Vector3d& anchor, const Eigen::Vector3d& axis) {
  dMass mass;
  dBodyGetMass(body, &mass);
  Eigen::Matrix3d inertia;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) inertia(r, c) = mass.I[4 * r + c];
  }
  const Eigen::Isometry3d pose = BodyPose(body);
  const Eigen::Vector3d a_body = pose.linear().transpose() * axis;
  const Eigen::Vector3d lever = (pose.translation() - anchor).cross(axis);
  return a_body.dot(inertia * a_body) + mass.mass * lever.squaredNorm();
}

}  // namespace

double SoftFingerSpinArm(double mu, double patch_radius) {
  if (!(mu >= 0) || !std::isfinite(mu) || !(patch_radius >= 0) || !std::isfinite(patch_radius)) {
    throw std::invalid_argument("SoftFingerSpinArm: mu and the patch radius must be finite, >= 0");
  }
  return 3.0 * kPi / 16.0 * mu * patch_radius;
}

// --- Implementation state -----------------------------------------------------------------------

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
  dContact contact_buffer[kMaxContactsPerPair];

  ~Impl() {
    for (dGeomID g : hand_geom) dGeomDestroy(g);
    for (dGeomID g : object_geom) dGeomDestroy(g);
    for (dTriMeshDataID d : mesh_data) dGeomTriMeshDataDestroy(d);
    if (contact_group) dJointGroupDestroy(contact_group);
    if (world) dWorldDestroy(world);
  }

  dGeomID MakeGeom(const SimShape& s) {
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

  // Attaches `geom` to `body` with the shape's pose relative to the body origin (= com).
  static void Attach(dGeomID geom, dBodyID body, const Eigen::Isometry3d& frame_from_shape,
                     const Eigen::Vector3d& com) {
    dGeomSetBody(geom, body);
    const Eigen::Vector3d t = frame_from_shape.translation() - com;
    dGeomSetOffsetPosition(geom, t.x(), t.y(), t.z());
    dMatrix3 r;
    ToOdeMatrix(frame_from_shape.linear(), r);
    dGeomSetOffsetRotation(geom, r);
  }

  Eigen::Isometry3d LinkPose(int i) const {
    Eigen::Isometry3d pose = BodyPose(link_body[i]);
    pose.translate(-link_com[i]);
    return pose;
  }

  Eigen::Isometry3d ObjectPose() const {
    Eigen::Isometry3d pose = BodyPose(object_body);
    pose.translate(-object_com);
    return pose;
  }

  // Kinematic forward kinematics from the start configuration:
  // T_i(q) = T_parent(q) · T_parent_start⁻¹ · Rot(anchor, axis, q_i − q_start,i) · T_i,start.
  void KinematicPoses(double t, std::vector<Eigen::Isometry3d>* poses) const {
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

  // Kinematic mode: puts every link exactly at its scheduled pose for time t and gives it the
  // velocity that reaches the pose of t + dt (ODE integrates kinematic bodies with it).
  void PlaceKinematic(double t) {
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

  // Motorized mode: velocity command of the position loop, torque-limited by the motor.
  void ApplyMotors() {
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

  // Hand–object narrow phase. Fills state->contacts; with create_joints also adds one contact
  // joint per point (Coulomb pyramid via dContactApprox1, soft ERP/CFM).
  void Collide(bool create_joints, SimState* state) {
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

  // Reads poses, joint angles and velocities, and checks for a numerical blow-up.
  void ReadState(SimState* state) const {
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
        reason = "speed " + std::to_string(v.norm()) + " m/s";
      } else if (w.norm() > options.blowup_angular_speed) {
        reason = "angular speed " + std::to_string(w.norm()) + " rad/s";
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
      state->blowup_reason += " at t = " + std::to_string(state->time) + " s";
    }
  }

  double ScheduledAngle(int i, double t) const {
    const double s = options.kinematic_close_time > 0
                         ? std::clamp(t / options.kinematic_close_time, 0.0, 1.0)
                         : 1.0;
    return hand.links[i].q_start + s * (q_target[i] - hand.links[i].q_start);
  }
};

// --- Construction -------------------------------------------------------------------------------

GraspSimulation::GraspSimulation(const OdeRuntime& /*runtime*/, const SimHand& hand,
                                 const SimObject& object, const SimOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Validate(hand, object, options);
  Impl& m = *impl_;
  m.hand = hand;
  m.options = options;
  const int n = static_cast<int>(hand.links.size());

  m.world = dWorldCreate();
  dWorldSetGravity(m.world, 0, 0, 0);
  dWorldSetERP(m.world, options.erp);
  dWorldSetCFM(m.world, options.cfm);
  dWorldSetContactSurfaceLayer(m.world, options.surface_layer);
  dWorldSetContactMaxCorrectingVel(m.world, options.max_correcting_velocity);
  dWorldSetQuickStepNumIterations(m.world, options.quickstep_iterations);
  dWorldSetAutoDisableFlag(m.world, 0);
  m.contact_group = dJointGroupCreate(0);

  // Hand links: bodies with the centre of mass at the body origin; geoms attached with offsets.
  m.link_body.resize(n);
  m.link_com.resize(n);
  m.hinge.assign(n, nullptr);
  m.lo_stop.assign(n, 0.0);
  m.hi_stop.assign(n, 0.0);
  m.axis_inertia.assign(n, 0.0);
  m.q_target.resize(n);
  m.kin_pose.resize(n);
  for (int i = 0; i < n; ++i) {
    const SimHandLink& l = m.hand.links[i];  // the copy: trimesh storage must outlive geoms
    Eigen::Vector3d com;
    dMass mass = CentredMass(l.shapes, l.mass, &com);
    m.link_com[i] = com;
    m.q_target[i] = i == 0 ? 0.0 : l.q_target;
    dBodyID body = dBodyCreate(m.world);
    dBodySetMass(body, &mass);
    Eigen::Isometry3d body_pose = l.world_from_link;
    body_pose.translate(com);
    SetBodyPose(body, body_pose);
    if (i == 0 || options.hand_mode == HandMode::kKinematic) dBodySetKinematic(body);
    m.link_body[i] = body;
    for (const SimShape& s : l.shapes) {
      dGeomID g = m.MakeGeom(s);
      Impl::Attach(g, body, s.body_from_shape, com);
      m.hand_geom.push_back(g);
      m.hand_geom_link.push_back(i);
    }
  }
  if (options.hand_mode == HandMode::kMotorized) {
    for (int i = 1; i < n; ++i) {
      const SimHandLink& l = m.hand.links[i];
      dJointID j = dJointCreateHinge(m.world, nullptr);
      // Body 1 = child, body 2 = parent: the hinge angle is the child's rotation relative to the
      // parent about the axis, zero at the start configuration.
      dJointAttach(j, m.link_body[i], m.link_body[l.parent]);
      dJointSetHingeAnchor(j, l.joint_anchor.x(), l.joint_anchor.y(), l.joint_anchor.z());
      const Eigen::Vector3d a = l.joint_axis.normalized();
      dJointSetHingeAxis(j, a.x(), a.y(), a.z());
      m.lo_stop[i] = std::max(l.lower - l.q_start, -kPi + 1e-3);
      m.hi_stop[i] = std::min(l.upper - l.q_start, kPi - 1e-3);
      dJointSetHingeParam(j, dParamLoStop, m.lo_stop[i]);
      dJointSetHingeParam(j, dParamHiStop, m.hi_stop[i]);
      m.axis_inertia[i] = AxisInertia(m.link_body[i], l.joint_anchor, a);
      dJointSetHingeParam(j, dParamStopERP, 0.2);
      dJointSetHingeParam(j, dParamStopCFM, 1e-5);
      dJointSetHingeParam(j, dParamFMax, l.max_torque);
      dJointSetHingeParam(j, dParamVel, 0.0);
      m.hinge[i] = j;
    }
  }

  // Object: one free body at its centre of mass.
  {
    m.object = object;
    dMass mass = CentredMass(object.shapes, object.mass, &m.object_com);
    m.object_body = dBodyCreate(m.world);
    dBodySetMass(m.object_body, &mass);
    Eigen::Isometry3d body_pose = object.world_from_object;
    body_pose.translate(m.object_com);
    SetBodyPose(m.object_body, body_pose);
    for (const SimShape& s : m.object.shapes) {
      dGeomID g = m.MakeGeom(s);
      Impl::Attach(g, m.object_body, s.body_from_shape, m.object_com);
      m.object_geom.push_back(g);
    }
  }
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

ObjectMass ObjectMassProperties(const SimObject& object) {
  ObjectMass out;
  const dMass mass = CentredMass(object.shapes, object.mass, &out.com);
  out.mass = mass.mass;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.inertia(r, c) = mass.I[4 * r + c];
  }
  return out;
}

}  // namespace planning::physics
