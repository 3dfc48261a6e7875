// AxisAlignmentFeature (planning/features/axis_alignment_feature.h) and its factory
// MakeAxisAlignmentFeature.
#include "planning/features/axis_alignment_feature.h"

#include <stdexcept>

#include "planning/features/internal/feature_helpers.h"

namespace planning {

using internal::JacobianData;

std::unique_ptr<FeatureData> AxisAlignmentFeature::CreateData(const Robot& robot) const {
  return std::make_unique<JacobianData>(6, num_dofs(robot));
}

void AxisAlignmentFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                                Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  const Eigen::Vector3d a = kin.world_from_link[link_].linear() * axis_;
  y[0] = a.dot(dir_);
  if (J != nullptr) {
    auto* d = static_cast<JacobianData*>(data);
    FrameJacobian(robot, kin, link_, d->jac);
    J->noalias() = a.cross(dir_).transpose() * d->jac.bottomRows<3>();
  }
}

std::unique_ptr<Feature> MakeAxisAlignmentFeature(const Robot& robot, int link,
                                                  const Eigen::Vector3d& axis_link,
                                                  const Eigen::Vector3d& direction_world) {
  internal::CheckLink(robot, link, "axis_alignment feature");
  if (axis_link.norm() < 1e-12 || direction_world.norm() < 1e-12 || !axis_link.allFinite() ||
      !direction_world.allFinite()) {
    throw std::invalid_argument("axis_alignment feature: axis and direction must be non-zero");
  }
  return std::make_unique<AxisAlignmentFeature>(link, axis_link, direction_world);
}

}  // namespace planning
