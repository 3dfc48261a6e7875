// Private: ClearanceFeature (planning/grasp/internal/clearance_feature.h).
#include "planning/grasp/internal/clearance_feature.h"

#include <algorithm>
#include <limits>

#include "planning/robot/kinematics.h"

namespace planning::internal {
namespace {

struct PointJacobianData : FeatureData {
  PointJacobianData(int n, int groups) : jp(3, n), best(groups), best_k(groups) {}
  Eigen::MatrixXd jp;
  std::vector<double> best;
  std::vector<int> best_k;
};

}  // namespace

std::unique_ptr<FeatureData> ClearanceFeature::CreateData(const Robot& robot) const {
  return std::make_unique<PointJacobianData>(num_dofs(robot), num_groups_);
}

void ClearanceFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  auto* d = static_cast<PointJacobianData*>(data);
  if (J) J->setZero();
  std::vector<double>& best = d->best;
  std::vector<int>& best_k = d->best_k;
  std::fill(best.begin(), best.end(), std::numeric_limits<double>::infinity());
  std::fill(best_k.begin(), best_k.end(), -1);
  if (mode_ == Mode::kHinge) y.setZero();
  for (size_t k = 0; k < spheres_.link.size(); ++k) {
    const int li = spheres_.link[k];
    const Eigen::Vector3d c = spheres_.center_local.col(k);
    const Eigen::Vector3d pw = kin.world_from_link[li] * c;
    Eigen::Vector3d g;
    const double dist =
        SignedDistance(object_, object_from_world_ * pw, J ? &g : nullptr) - spheres_.radius[k];
    if (mode_ == Mode::kHinge) {
      if (dist < margin_) {
        y[k] = margin_ - dist;
        if (J) {
          PointJacobian(robot, kin, li, c, d->jp);
          J->row(k) = -(world_from_object_.linear() * g).transpose() * d->jp;
        }
      }
    } else if (group_[k] >= 0 && dist < best[group_[k]]) {
      best[group_[k]] = dist;
      best_k[group_[k]] = static_cast<int>(k);
    }
  }
  if (mode_ == Mode::kMin) {
    for (int gi = 0; gi < num_groups_; ++gi) {
      y[gi] = best_k[gi] < 0 ? 0.0 : best[gi];
      if (J && best_k[gi] >= 0) {
        const int k = best_k[gi];
        const int li = spheres_.link[k];
        const Eigen::Vector3d c = spheres_.center_local.col(k);
        Eigen::Vector3d g;
        SignedDistance(object_, object_from_world_ * (kin.world_from_link[li] * c), &g);
        PointJacobian(robot, kin, li, c, d->jp);
        J->row(gi) = (world_from_object_.linear() * g).transpose() * d->jp;
      }
    }
  }
}

}  // namespace planning::internal
