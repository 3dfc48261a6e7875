// Private: GraspWindingFeature, the winding term of the grasp transfer (grasp_transfer.cc).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "planning/features/feature.h"
#include "planning/grasp/grasp_object.h"

namespace planning::internal {

// For the hand's finger chains (`chains`, C of them):
//   y = (per-finger winding about `reference` as EncodeGrasp (C; only when `main`), then per extra
//        reference curve r the opposition pair (max_f, min_f) of the finger values
//        (OppositionPair; 2 each)),
// dim = C·main + 2·|extra|, J = ∂y/∂q (dim × n). FeatureData: chain points, gradients and writhe
// workspaces (sized on first use, then reused without allocation).
class GraspWindingFeature : public Feature {
 public:
  GraspWindingFeature(std::vector<int> chains, ReferenceCurve reference,
                      std::vector<ReferenceCurve> extra, bool main)
      : chains_(std::move(chains)),
        reference_(std::move(reference)),
        extra_(std::move(extra)),
        main_(main) {}
  int dim() const override {
    return static_cast<int>((main_ ? chains_.size() : 0) + 2 * extra_.size());
  }
  std::string name() const override { return "grasp_winding"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  std::vector<int> chains_;
  ReferenceCurve reference_;
  std::vector<ReferenceCurve> extra_;
  bool main_;
};

}  // namespace planning::internal
