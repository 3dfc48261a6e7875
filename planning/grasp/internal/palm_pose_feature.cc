// Private: PalmPoseFeature (planning/grasp/internal/palm_pose_feature.h).
#include "planning/grasp/internal/palm_pose_feature.h"

namespace planning::internal {

void PalmPoseFeature::Eval(const Robot&, const KinematicsData& kin, FeatureData*,
                           Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  y = kin.q.head<6>();
  if (J) {
    J->setZero();
    J->leftCols<6>().setIdentity();
  }
}

}  // namespace planning::internal
