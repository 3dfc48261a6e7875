// WindingFeature: the winding number of a robot chain about an axis. Create it with
// MakeWindingFeature (planning/features/feature.h), which checks the arguments.
#pragma once

#include <memory>
#include <string>

#include "planning/features/feature.h"
#include "topology/winding.h"

namespace planning {

// y = topology::WindingNumber(P(q), axis) (signed variant; dim 1) for the chain points P(q)
// (3 × N, ChainPoints), J = Σ_k (∂w/∂p_k)ᵀ ∂p_k/∂q (1 × n). FeatureData: chain points, chain
// Jacobian and the gradient (3 × N). `chain` must be valid and the axis direction non-zero.
class WindingFeature : public Feature {
 public:
  WindingFeature(const Robot& robot, int chain, const topology::Axis& axis)
      : chain_(chain), axis_(axis), points_(ChainSize(robot, chain)) {}
  int dim() const override { return 1; }
  std::string name() const override { return "winding"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;
  bool queries_world() const override { return true; }
  // state_queries = Evals, distance_pair_tests = Evals × (ChainSize − 1) segments.
  QueryCounts query_counts(const FeatureData* data) const override;

 private:
  int chain_;
  topology::Axis axis_;
  int points_;
};

}  // namespace planning
