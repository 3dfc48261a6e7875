// PositionFeature (planning/features/position_feature.h) and its factory MakePositionFeature.
#include "planning/features/position_feature.h"

#include <memory>

#include "planning/features/internal/feature_helpers.h"

namespace planning {

void PositionFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData*,
                           Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  y = kin.world_from_link[link_] * offset_;
  if (J != nullptr) PointJacobian(robot, kin, link_, offset_, *J);
}

std::unique_ptr<Feature> MakePositionFeature(const Robot& robot, int link,
                                             const Eigen::Vector3d& offset) {
  internal::CheckLink(robot, link, "position feature");
  return std::make_unique<PositionFeature>(link, offset);
}

}  // namespace planning
