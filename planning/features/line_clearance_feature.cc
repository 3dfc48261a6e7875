// LineClearanceFeature (planning/features/line_clearance_feature.h) and its factory
// MakeLineClearanceFeature.
#include "planning/features/line_clearance_feature.h"

#include <algorithm>
#include <stdexcept>

#include "planning/features/internal/feature_helpers.h"

namespace planning {

using internal::ChainData;

std::unique_ptr<FeatureData> LineClearanceFeature::CreateData(const Robot& robot) const {
  return std::make_unique<ChainData>(points_, num_dofs(robot));
}

void LineClearanceFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                                Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  auto* d = static_cast<ChainData*>(data);
  ++d->evaluations;
  ChainPoints(robot, kin, chain_, &d->P);
  y.setZero();
  if (J != nullptr) {
    J->setZero();
    ChainJacobian(robot, kin, chain_, d->dP);
  }
  const Eigen::Matrix3d perp = Eigen::Matrix3d::Identity() - dir_ * dir_.transpose();
  for (int s = 0; s + 1 < points_; ++s) {
    // Components perpendicular to the line: a(σ) = a0 + σ·v, σ ∈ [0, 1]; d = min_σ |a(σ)|.
    const Eigen::Vector3d a0 = perp * (d->P.col(s) - point_);
    const Eigen::Vector3d v = perp * (d->P.col(s + 1) - d->P.col(s));
    const double vv = v.squaredNorm();
    const double sigma = vv > 1e-18 ? std::clamp(-a0.dot(v) / vv, 0.0, 1.0) : 0.5;
    const Eigen::Vector3d a = a0 + sigma * v;
    const double dist = a.norm();
    if (dist >= margin_) continue;
    y[s] = 1.0 - dist / margin_;
    if (J == nullptr || dist < 1e-12) continue;
    // ∂d/∂p_s = (1 − σ) nᵀ, ∂d/∂p_{s+1} = σ nᵀ (n = a/d ⊥ line; σ is stationary or clamped).
    const Eigen::RowVector3d n = a.transpose() / dist;
    J->row(s).noalias() -= ((1.0 - sigma) / margin_) * n * d->dP.middleRows<3>(3 * s);
    J->row(s).noalias() -= (sigma / margin_) * n * d->dP.middleRows<3>(3 * s + 3);
  }
}

std::unique_ptr<Feature> MakeLineClearanceFeature(const Robot& robot, int chain,
                                                  const topology::Axis& line, double margin) {
  internal::CheckChain(robot, chain, "line_clearance feature");
  if (!(line.direction.norm() > 1e-12) || !line.direction.allFinite() || !line.point.allFinite()) {
    throw std::invalid_argument(
        "line_clearance feature: the line needs a finite non-zero direction");
  }
  if (!(margin > 0.0)) throw std::invalid_argument("line_clearance feature: margin must be > 0");
  return std::make_unique<LineClearanceFeature>(robot, chain, line, margin);
}

QueryCounts LineClearanceFeature::query_counts(const FeatureData* data) const {
  if (data == nullptr) return {};
  const long evals = static_cast<const ChainData*>(data)->evaluations;
  return {evals, 0, evals * (points_ - 1)};
}

}  // namespace planning
