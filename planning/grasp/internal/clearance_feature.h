// Private: ClearanceFeature, the hand-sphere clearance and contact terms of the grasp transfer
// (grasp_transfer.cc).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "planning/features/feature.h"
#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"

namespace planning::internal {

// Clearance of every hand sphere k (centre c_k in its link, radius r_k) to the object:
// d_k = sdf(c_k) − r_k (world), and
//   kHinge:  y_k = max(0, margin − d_k) (dim = number of spheres, target 0: no penetration),
//            J_k = −∇sdfᵀ J_c if active;
//   kMin:    one output per group of spheres (dim num_groups; spheres with group −1 take no
//            part), y_g = min_{k ∈ g} d_k (0 for an empty group; target 0: touching),
//            J_g = ∇sdfᵀ J_c of the minimising sphere.
// J_c is the 3 × n point Jacobian of the sphere centre (the FeatureData holds it and the per-group
// minima). `group` has one entry per sphere.
class ClearanceFeature : public Feature {
 public:
  enum class Mode { kHinge, kMin };
  ClearanceFeature(HandSpheres spheres, std::vector<int> group, int num_groups,
                   const GraspObject& object, const Eigen::Isometry3d& world_from_object,
                   double margin, Mode mode)
      : spheres_(std::move(spheres)),
        group_(std::move(group)),
        num_groups_(num_groups),
        object_(object),
        world_from_object_(world_from_object),
        object_from_world_(world_from_object.inverse()),
        margin_(margin),
        mode_(mode) {}
  int dim() const override {
    return mode_ == Mode::kHinge ? static_cast<int>(spheres_.link.size()) : num_groups_;
  }
  std::string name() const override { return mode_ == Mode::kHinge ? "clearance" : "contact"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  HandSpheres spheres_;
  std::vector<int> group_;
  int num_groups_;
  GraspObject object_;
  Eigen::Isometry3d world_from_object_, object_from_world_;
  double margin_;
  Mode mode_;
};

}  // namespace planning::internal
