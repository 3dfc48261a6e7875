#include "planning/robot/pose.h"

#include <algorithm>
#include <cmath>

namespace planning {

Eigen::Isometry3d PoseFromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = xyz;
  t.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return t;
}

void PoseToXyzRpy(const Eigen::Isometry3d& pose, Eigen::Vector3d* xyz, Eigen::Vector3d* rpy) {
  *xyz = pose.translation();
  const Eigen::Matrix3d& r = pose.linear();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  double roll, yaw;
  if (std::abs(std::cos(pitch)) > 1e-9) {
    roll = std::atan2(r(2, 1), r(2, 2));
    yaw = std::atan2(r(1, 0), r(0, 0));
  } else {
    roll = 0.0;
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  *rpy = Eigen::Vector3d(roll, pitch, yaw);
}

Eigen::Matrix3d RotationFromZ(const Eigen::Vector3d& d) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d).toRotationMatrix();
}

}  // namespace planning
