// AxisAlignmentFeature: how well a link axis points along a world direction. Create it with
// MakeAxisAlignmentFeature (planning/features/feature.h), which checks the arguments.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "planning/features/feature.h"

namespace planning {

// y = (R_link a)·d ∈ [−1, 1] (dim 1; 1 = aligned) for the link axis a (link frame) and the world
// direction d, both normalised here; J = ((R_link a) × d)ᵀ J_ω (1 × n), J_ω the angular rows of
// FrameJacobian (its 6 × n buffer is the FeatureData). `link` must be a valid link index and
// a, d non-zero.
class AxisAlignmentFeature : public Feature {
 public:
  AxisAlignmentFeature(int link, const Eigen::Vector3d& axis, const Eigen::Vector3d& dir)
      : link_(link), axis_(axis.normalized()), dir_(dir.normalized()) {}
  int dim() const override { return 1; }
  std::string name() const override { return "axis_alignment"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  int link_;
  Eigen::Vector3d axis_, dir_;
};

}  // namespace planning
