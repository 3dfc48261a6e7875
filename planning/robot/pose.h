// Rigid poses written as URDF writes them: a translation xyz [m] and roll-pitch-yaw angles [rad].
#pragma once

#include <Eigen/Geometry>

namespace planning {

// Pose from translation xyz and roll-pitch-yaw (URDF convention R = Rz(y)·Ry(p)·Rx(r)).
Eigen::Isometry3d PoseFromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);
// Inverse of PoseFromXyzRpy (rpy with pitch in [−π/2, π/2]).
void PoseToXyzRpy(const Eigen::Isometry3d& pose, Eigen::Vector3d* xyz, Eigen::Vector3d* rpy);

}  // namespace planning
