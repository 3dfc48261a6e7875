// PositionFeature: the world position of a point fixed in a link. Create it with
// MakePositionFeature (planning/features/feature.h), which checks the arguments.
#pragma once

#include <Eigen/Core>
#include <string>

#include "planning/features/feature.h"

namespace planning {

// y = T_link · offset ∈ R³ (world frame, dim 3), J = PointJacobian(link, offset) (3 × n). Needs no
// FeatureData. `link` must be a valid link index.
class PositionFeature : public Feature {
 public:
  PositionFeature(int link, const Eigen::Vector3d& offset) : link_(link), offset_(offset) {}
  int link() const { return link_; }                         // the link index
  const Eigen::Vector3d& offset() const { return offset_; }  // the point, link frame, m
  int dim() const override { return 3; }
  std::string name() const override { return "position"; }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  int link_;
  Eigen::Vector3d offset_;
};

}  // namespace planning
