// The collision feature (declared in planning/features/feature.h): FCL proximity pairs as per-link hinges.
#include <stdexcept>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/features/feature.h"

namespace planning {
namespace {

struct CollisionFeatureData : FeatureData {
  CollisionFeatureData(const Robot& robot, const Environment& env, const CollisionOptions& options)
      : coll(robot, env, options) {
    pairs.reserve(64);
  }
  CollisionData coll;
  std::vector<ProximityPair> pairs;
};

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
  std::unique_ptr<FeatureData> CreateData(const Robot& robot) const override {
    return std::make_unique<CollisionFeatureData>(robot, *env_, options_);
  }
  long collision_queries(const FeatureData* data) const override {
    return data == nullptr
               ? 0
               : static_cast<long>(static_cast<const CollisionFeatureData*>(data)->coll.queries);
  }
  long narrow_phase_calls(const FeatureData* data) const override {
    return data == nullptr
               ? 0
               : static_cast<long>(
                     static_cast<const CollisionFeatureData*>(data)->coll.narrow_phase_calls);
  }
  void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const override {
    auto* d = static_cast<CollisionFeatureData*>(data);
    ComputeProximity(robot, kin, margin_, &d->coll, &d->pairs);
    y.setZero();
    if (J != nullptr) J->setZero();
    for (const ProximityPair& p : d->pairs) {
      if (p.distance >= margin_) continue;
      y[p.link_a] += 1.0 - p.distance / margin_;
      if (J == nullptr) continue;
      // ∂d/∂q = nᵀ (J_a(p_a) − J_b(p_b)) with n the unit vector from p_b to p_a (for separated
      // pairs it is computed from the witness points, which fixes its sign whatever the
      // narrow-phase convention; penetrating pairs use the reported normal).
      Eigen::Vector3d n = p.point_a - p.point_b;
      const double len = n.norm();
      if (p.distance > 0.0 && len > 1e-9) {
        n /= len;
      } else {
        n = p.normal;
      }
      AddPointJacobianAlong(robot, kin, p.link_a, p.point_a, n, -1.0 / margin_, J->row(p.link_a));
      if (p.link_b >= 0) {
        AddPointJacobianAlong(robot, kin, p.link_b, p.point_b, n, 1.0 / margin_, J->row(p.link_a));
      }
    }
  }

 private:
  const Environment* env_;
  CollisionOptions options_;
  double margin_;
  int links_;
};

}  // namespace

std::unique_ptr<Feature> MakeCollisionFeature(const Robot& robot, const Environment& env,
                                              const CollisionOptions& options, double margin) {
  if (!(margin > 0.0)) throw std::invalid_argument("collision feature: margin must be > 0");
  return std::make_unique<CollisionFeature>(robot, env, options, margin);
}

}  // namespace planning
