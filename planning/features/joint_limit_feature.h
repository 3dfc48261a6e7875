// JointLimitFeature: joint limits as a hinge per dof. Create it with MakeJointLimitFeature
// (planning/features/feature.h), which checks the margin.
#pragma once

#include <Eigen/Core>
#include <string>

#include "planning/features/feature.h"

namespace planning {

// Per dof k (dim n = num_dofs, target 0), with lo_k = lower_k + m_k and hi_k = upper_k − m_k:
//   y_k = max(0, lo_k − q_k) − max(0, q_k − hi_k),
// J = −I on the violated rows, 0 elsewhere (n × n). m_k is `margin` [rad] for revolute and
// continuous joints, `prismatic_margin` [m] for prismatic ones, at most 45 % of the joint's range
// (so lo_k < hi_k). Infinite limits never activate. Needs no FeatureData. Margins >= 0.
class JointLimitFeature : public Feature {
 public:
  JointLimitFeature(const Robot& robot, double margin, double prismatic_margin = 0.0);
  int dim() const override { return static_cast<int>(lo_.size()); }
  std::string name() const override { return "joint_limits"; }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  Eigen::VectorXd lo_, hi_;  // the limits moved inwards by each joint's margin
};

}  // namespace planning
