// CollisionFeature: collision avoidance against an environment (and self-collision) as per-link
// hinges on FCL proximity pairs. Create it with MakeCollisionFeature (planning/features/feature.h),
// which checks the margin.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "planning/collision/collision.h"
#include "planning/features/feature.h"

namespace planning {

// Per robot link k (dim = number of links, target 0), over the proximity pairs p closer than
// `margin` (ComputeProximity; signed distance d_p, witness points, normal n_p from b to a):
//   y_k = Σ_{p : link_a(p) = k} (1 − d_p / margin),
// ∂y_k/∂q = −(1/margin) Σ_p n_pᵀ (J_a(p_a) − J_b(p_b)) (J_b = 0 for environment objects; 1 × n
// per row). FeatureData: a CollisionData and the pair buffer; each Eval makes one query (counted by
// collision_queries). `env` must outlive the feature; margin > 0.
class CollisionFeature : public Feature {
 public:
  CollisionFeature(const Robot& robot, const Environment& env, const CollisionOptions& options,
                   double margin)
      : env_(&env),
        options_(options),
        margin_(margin),
        links_(static_cast<int>(robot.links.size())) {}
  int dim() const override { return links_; }
  std::string name() const override { return "collision"; }
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override;
  long collision_queries(const FeatureData* data) const override;
  long narrow_phase_calls(const FeatureData* data) const override;
  bool queries_world() const override { return true; }
  QueryCounts query_counts(const FeatureData* data) const override;  // Counts(its CollisionData)
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override;

 private:
  const Environment* env_;
  CollisionOptions options_;
  double margin_;
  int links_;
};

}  // namespace planning
