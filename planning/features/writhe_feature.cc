// WritheFeature (planning/features/writhe_feature.h) and its factory MakeWritheFeature.
#include "planning/features/writhe_feature.h"

#include <stdexcept>

#include "planning/features/internal/feature_helpers.h"
#include "topology/writhe.h"

namespace planning {

using internal::ChainData;

std::unique_ptr<FeatureData> WritheFeature::CreateData(const Robot& robot) const {
  auto d = std::make_unique<ChainData>(rows_ + 1, num_dofs(robot));
  d->W.resize(rows_, cols_);
  d->dW.resize(rows_ * cols_, num_dofs(robot));
  return d;
}

void WritheFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                         Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  auto* d = static_cast<ChainData*>(data);
  ChainPoints(robot, kin, chain_, &d->P);
  topology::WritheOptions options;
  if (J == nullptr) {
    topology::WritheMatrix(d->P, object_, options, &d->W, &d->ws);
  } else {
    topology::WritheMatrixWithJacobian(d->P, object_, options, &d->W, &d->wjac, &d->ws);
    ChainJacobian(robot, kin, chain_, d->dP);
  }
  if (output_ == WritheOutput::kTotal) {
    y[0] = d->W.sum();
    if (J != nullptr) {
      // ∂Σ/∂q = Σ_k (∂Σ/∂p_k)ᵀ ∂p_k/∂q.
      topology::WeightedWritheGradient(d->wjac, Eigen::MatrixXd(), &d->grad, &d->grad_object);
      J->noalias() = Eigen::Map<const Eigen::RowVectorXd>(d->grad.data(), d->grad.size()) * d->dP;
    }
  } else {
    for (int i = 0; i < rows_; ++i) {
      for (int j = 0; j < cols_; ++j) y[i * cols_ + j] = d->W(i, j);
    }
    if (J != nullptr) {
      topology::ChainWritheJacobian(d->wjac, d->dP, Eigen::MatrixXd(), J);
    }
  }
}

std::unique_ptr<Feature> MakeWritheFeature(const Robot& robot, int chain,
                                           const Eigen::Matrix3Xd& object_chain,
                                           WritheOutput output) {
  internal::CheckChain(robot, chain, "writhe feature");
  if (object_chain.cols() < 2 || !object_chain.allFinite()) {
    throw std::invalid_argument("writhe feature: the object chain needs >= 2 finite points");
  }
  return std::make_unique<WritheFeature>(robot, chain, object_chain, output);
}

}  // namespace planning
