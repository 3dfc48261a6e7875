// BoxFeature: keeps a point of a link inside an axis-aligned world box. Create it with
// MakeBoxFeature (planning/features/feature.h), which checks the arguments.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "planning/features/feature.h"

namespace planning {

// For the point p = T_link · offset (world), per world axis k (dim 3, target 0), with
// lo = c − h + margin and hi = c + h − margin (centre c, half-extents h):
//   y_k = max(0, p_k − hi_k) − max(0, lo_k − p_k),
// J row k = row k of PointJacobian(link, offset) where active, 0 elsewhere (3 × n; the 3 × n
// point Jacobian is the FeatureData). `link` must be valid and h > margin >= 0.
class BoxFeature : public Feature {
 public:
  BoxFeature(int link, const Eigen::Vector3d& offset, const Eigen::Vector3d& c,
             const Eigen::Vector3d& h, double margin)
      : link_(link),
        offset_(offset),
        lo_(c - h + Eigen::Vector3d::Constant(margin)),
        hi_(c + h - Eigen::Vector3d::Constant(margin)) {}
  int dim() const override { return 3; }
  std::string name() const override { return "box"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  int link_;
  Eigen::Vector3d offset_, lo_, hi_;
};

}  // namespace planning
