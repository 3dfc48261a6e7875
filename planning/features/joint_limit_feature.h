// JointLimitFeature: joint limits as a hinge per dof. Create it with MakeJointLimitFeature
// (planning/features/feature.h), which checks the margin.
#pragma once

#include <Eigen/Core>
#include <string>

#include "planning/features/feature.h"

namespace planning {

// Per dof k (dim n = num_dofs, target 0), with lo_k = lower_k + margin and hi_k = upper_k − margin:
//   y_k = max(0, lo_k − q_k) − max(0, q_k − hi_k),
// J = −I on the violated rows, 0 elsewhere (n × n). Infinite limits never activate. Needs no
// FeatureData. margin >= 0.
class JointLimitFeature : public Feature {
 public:
  JointLimitFeature(const Robot& robot, double margin)
      : lower_(LowerLimits(robot)), upper_(UpperLimits(robot)), margin_(margin) {}
  int dim() const override { return static_cast<int>(lower_.size()); }
  std::string name() const override { return "joint_limits"; }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  Eigen::VectorXd lower_, upper_;
  double margin_;
};

}  // namespace planning
