// Private: PalmPoseFeature, the palm pose prior of the grasp transfer (grasp_transfer.cc).
#pragma once

#include <Eigen/Core>
#include <string>

#include "planning/features/feature.h"

namespace planning::internal {

// The floating base of a MakeFloatingHand robot itself: y = q[0..5] (palm translation and
// rotation joints; dim 6), J = [I₆ 0] (6 × n). Needs no FeatureData; n >= 6.
class PalmPoseFeature : public Feature {
 public:
  int dim() const override { return 6; }
  std::string name() const override { return "palm_pose"; }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;
};

}  // namespace planning::internal
