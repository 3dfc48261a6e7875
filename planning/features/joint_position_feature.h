// JointPositionFeature: the configuration itself ("qitself"). Create it with
// MakeJointPositionFeature (planning/features/feature.h).
#pragma once

#include <Eigen/Core>
#include <string>

#include "planning/features/feature.h"

namespace planning {

// y = q (dim n = num_dofs), J = I (n × n). Needs no FeatureData. With a velocity-order task and
// target 0 it is the joint-velocity regulariser ν||q̇||².
class JointPositionFeature : public Feature {
 public:
  explicit JointPositionFeature(int n) : n_(n) {}
  int dim() const override { return n_; }
  std::string name() const override { return "joint_position"; }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  int n_;
};

}  // namespace planning
