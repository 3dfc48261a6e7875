// LineClearanceFeature: keeps a robot chain off a line (e.g. a pole's axis). Create it with
// MakeLineClearanceFeature (planning/features/feature.h), which checks the arguments.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "planning/features/feature.h"
#include "topology/winding.h"

namespace planning {

// A hinge per chain segment s = [p_s, p_{s+1}] (dim = ChainSize − 1, target 0): with d_s the
// distance of the segment to the line (infinite both ways) and σ_s ∈ [0, 1] its closest segment
// parameter,
//   y_s = max(0, 1 − d_s / margin),
// J row s = −(1/margin) n_sᵀ ((1 − σ_s) ∂p_s/∂q + σ_s ∂p_{s+1}/∂q) where active (n_s the unit
// vector from the line to the closest point; 1 × n per row). FeatureData: chain points and chain
// Jacobian. `chain` must be valid, the direction finite and non-zero (normalised here),
// margin > 0.
class LineClearanceFeature : public Feature {
 public:
  LineClearanceFeature(const Robot& robot, int chain, const topology::Axis& line, double margin)
      : chain_(chain),
        point_(line.point),
        dir_(line.direction.normalized()),
        margin_(margin),
        points_(ChainSize(robot, chain)) {}
  int dim() const override { return points_ - 1; }
  std::string name() const override { return "line_clearance"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;
  bool queries_world() const override { return true; }
  // state_queries = Evals, distance_pair_tests = Evals × (ChainSize − 1) segments.
  QueryCounts query_counts(const FeatureData* data) const override;

 private:
  int chain_;
  Eigen::Vector3d point_, dir_;
  double margin_;
  int points_;
};

}  // namespace planning
