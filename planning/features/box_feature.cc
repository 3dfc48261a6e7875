// BoxFeature (planning/features/box_feature.h) and its factory MakeBoxFeature.
#include "planning/features/box_feature.h"

#include <algorithm>
#include <stdexcept>

#include "planning/features/internal/feature_helpers.h"

namespace planning {

using internal::JacobianData;

std::unique_ptr<FeatureData> BoxFeature::CreateData(const Robot& robot) const {
  return std::make_unique<JacobianData>(3, num_dofs(robot));
}

void BoxFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                      Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  const Eigen::Vector3d p = kin.world_from_link[link_] * offset_;
  auto* d = static_cast<JacobianData*>(data);
  if (J != nullptr) {
    PointJacobian(robot, kin, link_, offset_, d->jac);
    J->setZero();
  }
  for (int k = 0; k < 3; ++k) {
    y[k] = std::max(0.0, p[k] - hi_[k]) - std::max(0.0, lo_[k] - p[k]);
    if (J != nullptr && (p[k] > hi_[k] || p[k] < lo_[k])) J->row(k) = d->jac.row(k);
  }
}

std::unique_ptr<Feature> MakeBoxFeature(const Robot& robot, int link, const Eigen::Vector3d& offset,
                                        const Eigen::Vector3d& center,
                                        const Eigen::Vector3d& half_extent, double margin) {
  internal::CheckLink(robot, link, "box feature");
  if (!(half_extent.minCoeff() > margin) || !(margin >= 0.0)) {
    throw std::invalid_argument("box feature: half extents must exceed the margin (>= 0)");
  }
  return std::make_unique<BoxFeature>(link, offset, center, half_extent, margin);
}

}  // namespace planning
