// JointLimitFeature (planning/features/joint_limit_feature.h) and its factory
// MakeJointLimitFeature.
#include "planning/features/joint_limit_feature.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace planning {

JointLimitFeature::JointLimitFeature(const Robot& robot, double margin, double prismatic_margin)
    : lo_(LowerLimits(robot)), hi_(UpperLimits(robot)) {
  for (Eigen::Index k = 0; k < lo_.size(); ++k) {
    const Joint& joint = robot.joints[robot.dof_joints[k]];
    double m = joint.type == JointType::kPrismatic ? prismatic_margin : margin;
    const double range = hi_[k] - lo_[k];
    if (std::isfinite(range)) m = std::min(m, 0.45 * range);
    lo_[k] += m;
    hi_[k] -= m;
  }
}

void JointLimitFeature::Eval(const Robot&, const KinematicsData& kin, FeatureData*,
                             Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  if (J != nullptr) J->setZero();
  for (int k = 0; k < dim(); ++k) {
    const double q = kin.q[k];
    const double lo = lo_[k], hi = hi_[k];
    y[k] = 0.0;
    if (q < lo) {
      y[k] = lo - q;
      if (J != nullptr) (*J)(k, k) = -1.0;
    } else if (q > hi) {
      y[k] = -(q - hi);
      if (J != nullptr) (*J)(k, k) = -1.0;
    }
  }
}

std::unique_ptr<Feature> MakeJointLimitFeature(const Robot& robot, double margin,
                                               double prismatic_margin) {
  if (!(margin >= 0.0) || !(prismatic_margin >= 0.0))
    throw std::invalid_argument("joint_limits feature: margins must be >= 0");
  return std::make_unique<JointLimitFeature>(robot, margin, prismatic_margin);
}

}  // namespace planning
