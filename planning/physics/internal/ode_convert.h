// Private: conversions between Eigen and ODE (poses, rotation matrices, vectors) used by the grasp
// simulation (grasp_simulation*.cc).
#pragma once

#include <ode/ode.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace planning::physics::internal {

// World pose of an ODE body (its origin = centre of mass; quaternion normalised).
inline Eigen::Isometry3d BodyPose(dBodyID body) {
  const dReal* p = dBodyGetPosition(body);
  const dReal* q = dBodyGetQuaternion(body);  // (w, x, y, z)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return pose;
}

// Sets an ODE body's world pose (rotation as a quaternion).
inline void SetBodyPose(dBodyID body, const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
  dBodySetQuaternion(body, dq);
  const Eigen::Vector3d& t = pose.translation();
  dBodySetPosition(body, t.x(), t.y(), t.z());
}

// 3 × 3 rotation into ODE's row-major 3 × 4 dMatrix3 (4th column 0).
inline void ToOdeMatrix(const Eigen::Matrix3d& r, dMatrix3 out) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out[4 * i + j] = r(i, j);
    out[4 * i + 3] = 0;
  }
}

// ODE 3-vector as Eigen.
inline Eigen::Vector3d Vec(const dReal* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

inline bool Finite(const Eigen::Isometry3d& t) { return t.matrix().allFinite(); }

}  // namespace planning::physics::internal
