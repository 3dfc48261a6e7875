// WritheFeature: the writhe matrix (or its sum) between a robot chain and a static object chain.
// Create it with MakeWritheFeature (planning/features/feature.h), which checks the arguments.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "planning/features/feature.h"

namespace planning {

// For the robot chain points P(q) (3 × N_A, ChainPoints) and the object chain O (3 × N_B):
// W = topology::WritheMatrix(P, O) ((N_A−1) × (N_B−1), rows = robot segments).
//   kMatrix: y = vec(W) row-major (dim (N_A−1)(N_B−1)), J = ∂W/∂P · ∂P/∂q (ChainWritheJacobian);
//   kTotal:  y = Σ_ij W_ij (dim 1), J = Σ_k (∂Σ/∂p_k)ᵀ ∂p_k/∂q (1 × n).
// With closed_by_chord the robot chain is closed by its chord first: P gains its first point again
// as point N_A, so W has N_A rows (the last: the chord from the chain's end back to its start)
// and kMatrix has dim N_A(N_B−1). With O a straight pole axis, Σ W tells the turns the closed chain
// makes round the pole: it is the change of the solid angle the loop subtends, followed
// continuously along O from its first point to its last, over 4π; a whole number for an
// infinitely long pole, near one when O's ends are far from the loop.
// FeatureData: chain points, chain Jacobian, W and the writhe workspaces. `chain` must be valid
// and O have >= 2 finite points.
class WritheFeature : public Feature {
 public:
  WritheFeature(const Robot& robot, int chain, const Eigen::Matrix3Xd& object, WritheOutput out,
                bool closed_by_chord = false)
      : chain_(chain),
        object_(object),
        output_(out),
        closed_by_chord_(closed_by_chord),
        rows_(ChainSize(robot, chain) - (closed_by_chord ? 0 : 1)),
        cols_(static_cast<int>(object.cols()) - 1) {}
  int dim() const override { return output_ == WritheOutput::kTotal ? 1 : rows_ * cols_; }
  std::string name() const override {
    return output_ == WritheOutput::kTotal ? "writhe_total" : "writhe";
  }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  int chain_;
  Eigen::Matrix3Xd object_;
  WritheOutput output_;
  bool closed_by_chord_;
  int rows_, cols_;
};

}  // namespace planning
