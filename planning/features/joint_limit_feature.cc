// JointLimitFeature (planning/features/joint_limit_feature.h) and its factory
// MakeJointLimitFeature.
#include "planning/features/joint_limit_feature.h"

#include <memory>
#include <stdexcept>

namespace planning {

void JointLimitFeature::Eval(const Robot&, const KinematicsData& kin, FeatureData*,
                             Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  if (J != nullptr) J->setZero();
  for (int k = 0; k < dim(); ++k) {
    const double q = kin.q[k];
    const double lo = lower_[k] + margin_, hi = upper_[k] - margin_;
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

std::unique_ptr<Feature> MakeJointLimitFeature(const Robot& robot, double margin) {
  if (!(margin >= 0.0)) throw std::invalid_argument("joint_limits feature: margin must be >= 0");
  return std::make_unique<JointLimitFeature>(robot, margin);
}

}  // namespace planning
