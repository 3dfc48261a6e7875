// WritheFeature (planning/features/writhe_feature.h) and its factory MakeWritheFeature.
#include "planning/features/writhe_feature.h"

#include <stdexcept>

#include "planning/features/internal/feature_helpers.h"
#include "topology/writhe.h"

namespace planning {

using internal::ChainData;

std::unique_ptr<FeatureData> WritheFeature::CreateData(const Robot& robot) const {
  const int points = ChainSize(robot, chain_);
  auto d = std::make_unique<ChainData>(points, num_dofs(robot));
  if (closed_by_chord_) {
    d->closed_P.resize(3, points + 1);
    d->closed_dP.resize(3 * (points + 1), num_dofs(robot));
  }
  d->W.resize(rows_, cols_);
  d->dW.resize(rows_ * cols_, num_dofs(robot));
  return d;
}

void WritheFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                         Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  auto* d = static_cast<ChainData*>(data);
  ChainPoints(robot, kin, chain_, &d->P);
  if (J != nullptr) ChainJacobian(robot, kin, chain_, d->dP);
  const int points = static_cast<int>(d->P.cols());
  if (closed_by_chord_) {  // the chain's first point again, with its Jacobian rows
    d->closed_P.leftCols(points) = d->P;
    d->closed_P.col(points) = d->P.col(0);
    if (J != nullptr) {
      d->closed_dP.topRows(3 * points) = d->dP;
      d->closed_dP.bottomRows<3>() = d->dP.topRows<3>();
    }
  }
  const Eigen::Matrix3Xd& P = closed_by_chord_ ? d->closed_P : d->P;
  const Eigen::MatrixXd& dP = closed_by_chord_ ? d->closed_dP : d->dP;
  topology::WritheOptions options;
  if (J == nullptr) {
    topology::WritheMatrix(P, object_, options, &d->W, &d->ws);
  } else {
    topology::WritheMatrixWithJacobian(P, object_, options, &d->W, &d->wjac, &d->ws);
  }
  if (output_ == WritheOutput::kTotal) {
    y[0] = d->W.sum();
    if (J != nullptr) {
      // ∂Σ/∂q = Σ_k (∂Σ/∂p_k)ᵀ ∂p_k/∂q.
      topology::WeightedWritheGradient(d->wjac, Eigen::MatrixXd(), &d->grad, &d->grad_object);
      J->noalias() = Eigen::Map<const Eigen::RowVectorXd>(d->grad.data(), d->grad.size()) * dP;
    }
  } else {
    for (int i = 0; i < rows_; ++i) {
      for (int j = 0; j < cols_; ++j) y[i * cols_ + j] = d->W(i, j);
    }
    if (J != nullptr) {
      topology::ChainWritheJacobian(d->wjac, dP, Eigen::MatrixXd(), J);
    }
  }
}

std::unique_ptr<Feature> MakeWritheFeature(const Robot& robot, int chain,
                                           const Eigen::Matrix3Xd& object_chain,
                                           WritheOutput output, bool closed_by_chord) {
  internal::CheckChain(robot, chain, "writhe feature");
  if (object_chain.cols() < 2 || !object_chain.allFinite()) {
    throw std::invalid_argument("writhe feature: the object chain needs >= 2 finite points");
  }
  return std::make_unique<WritheFeature>(robot, chain, object_chain, output, closed_by_chord);
}

}  // namespace planning
