// Checks and mass properties of a grasp simulation's description (planning/physics/
// grasp_simulation.h): Validate, the shapes' masses (uniform density) re-centred for ODE, a link's
// inertia about its hinge axis, and ObjectMassProperties.
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "planning/physics/grasp_simulation.h"
#include "planning/physics/internal/grasp_simulation_impl.h"
#include "planning/physics/internal/ode_convert.h"

namespace planning::physics {
namespace internal {
namespace {

// Checks one shape's size, pose and (trimesh) vertices and triangles; `where` names it.
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

}  // namespace

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

}  // namespace internal

ObjectMass ObjectMassProperties(const SimObject& object) {
  ObjectMass out;
  const dMass mass = internal::CentredMass(object.shapes, object.mass, &out.com);
  out.mass = mass.mass;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.inertia(r, c) = mass.I[4 * r + c];
  }
  return out;
}

}  // namespace planning::physics
