// WindingFeature (planning/features/winding_feature.h) and its factory MakeWindingFeature.
#include "planning/features/winding_feature.h"

#include <stdexcept>

#include "planning/features/internal/feature_helpers.h"

namespace planning {

using internal::ChainData;

std::unique_ptr<FeatureData> WindingFeature::CreateData(const Robot& robot) const {
  auto d = std::make_unique<ChainData>(points_, num_dofs(robot));
  d->grad.resize(3, points_);
  return d;
}

void WindingFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                          Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  auto* d = static_cast<ChainData*>(data);
  ++d->evaluations;
  ChainPoints(robot, kin, chain_, &d->P);
  y[0] = topology::WindingNumber(d->P, axis_, {}, J != nullptr ? &d->grad : nullptr);
  if (J != nullptr) {
    ChainJacobian(robot, kin, chain_, d->dP);
    J->noalias() = Eigen::Map<const Eigen::RowVectorXd>(d->grad.data(), d->grad.size()) * d->dP;
  }
}

std::unique_ptr<Feature> MakeWindingFeature(const Robot& robot, int chain,
                                            const topology::Axis& axis) {
  internal::CheckChain(robot, chain, "winding feature");
  if (axis.direction.norm() < 1e-12) {
    throw std::invalid_argument("winding feature: zero axis direction");
  }
  return std::make_unique<WindingFeature>(robot, chain, axis);
}

QueryCounts WindingFeature::query_counts(const FeatureData* data) const {
  if (data == nullptr) return {};
  const long evals = static_cast<const ChainData*>(data)->evaluations;
  return {evals, 0, evals * (points_ - 1)};
}

}  // namespace planning
