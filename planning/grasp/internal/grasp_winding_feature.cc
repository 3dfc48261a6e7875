// Private: GraspWindingFeature (planning/grasp/internal/grasp_winding_feature.h).
#include "planning/grasp/internal/grasp_winding_feature.h"

#include "planning/grasp/grasp.h"
#include "planning/robot/kinematics.h"
#include "topology/winding.h"
#include "topology/writhe.h"

namespace planning::internal {
namespace {

// Buffers of GraspWindingFeature (sized on first use, then reused without allocation).
struct WindingData : FeatureData {
  Eigen::Matrix3Xd points, grad, grad_b;
  Eigen::MatrixXd dP, w;
  topology::WritheJacobian wj;
  topology::WritheWorkspace ws;
};

}  // namespace

std::unique_ptr<FeatureData> GraspWindingFeature::CreateData(const Robot&) const {
  return std::make_unique<WindingData>();
}

void GraspWindingFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                               Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
  auto* d = static_cast<WindingData*>(data);
  const int n = num_dofs(robot);
  if (J) J->setZero();
  for (size_t c = 0; main_ && c < chains_.size(); ++c) {
    ChainPoints(robot, kin, chains_[c], &d->points);
    const int np = static_cast<int>(d->points.cols());
    if (reference_.kind == ReferenceCurve::Kind::kAxis) {
      y[c] = topology::WindingNumber(d->points, reference_.axis, {}, J ? &d->grad : nullptr);
    } else {
      topology::WritheMatrixWithJacobian(d->points, reference_.loop, {}, &d->w, &d->wj, &d->ws);
      y[c] = d->w.sum();
      if (J) topology::WeightedWritheGradient(d->wj, Eigen::MatrixXd(), &d->grad, &d->grad_b);
    }
    if (J) {
      if (d->dP.rows() != 3 * np || d->dP.cols() != n) d->dP.resize(3 * np, n);
      ChainJacobian(robot, kin, chains_[c], d->dP);
      for (int k = 0; k < np; ++k) {
        J->row(c).noalias() += d->grad.col(k).transpose() * d->dP.middleRows(3 * k, 3);
      }
    }
  }
  const int nc = main_ ? static_cast<int>(chains_.size()) : 0;
  for (size_t r = 0; r < extra_.size(); ++r) {
    const int row = nc + 2 * static_cast<int>(r);
    Eigen::MatrixXd jf, jp;
    const Eigen::VectorXd w = EncodeGrasp(robot, kin, chains_, extra_[r], J ? &jf : nullptr).finger;
    y.segment<2>(row) = OppositionPair(w, J ? &jf : nullptr, &jp);
    if (J) J->middleRows(row, 2) = jp;
  }
}

}  // namespace planning::internal
