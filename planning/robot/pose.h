// Rigid poses written as URDF writes them: a translation xyz [m] and roll-pitch-yaw angles [rad].
#pragma once

#include <Eigen/Geometry>

namespace planning {

// Pose from translation xyz and roll-pitch-yaw (URDF convention R = Rz(y)·Ry(p)·Rx(r)).
Eigen::Isometry3d PoseFromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);
// Inverse of PoseFromXyzRpy (rpy with pitch in [−π/2, π/2]).
void PoseToXyzRpy(const Eigen::Isometry3d& pose, Eigen::Vector3d* xyz, Eigen::Vector3d* rpy);

// The shortest rotation R (3×3) with R·ẑ = d/|d|: Eigen's Quaternion::FromTwoVectors(ẑ, d), which
// for d along −ẑ picks a half turn about an axis ⟂ ẑ. d ≠ 0. Close to −ẑ (but not on it) its
// error grows as ε / (1 + cos∠(ẑ, d)): 5e-11 at 2 mrad from −ẑ. Kept out of line: FromTwoVectors
// instantiates a JacobiSVD, seconds of compile time in every file that calls it.
Eigen::Matrix3d RotationFromZ(const Eigen::Vector3d& d);

}  // namespace planning
