// JointPositionFeature (planning/features/joint_position_feature.h) and its factory
// MakeJointPositionFeature.
#include "planning/features/joint_position_feature.h"

#include <memory>

namespace planning {

void JointPositionFeature::Eval(const Robot&, const KinematicsData& kin, FeatureData*,
                                Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  y = kin.q;
  if (J != nullptr) J->setIdentity();
}

std::unique_ptr<Feature> MakeJointPositionFeature(const Robot& robot) {
  return std::make_unique<JointPositionFeature>(num_dofs(robot));
}

}  // namespace planning
