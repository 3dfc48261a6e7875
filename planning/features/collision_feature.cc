// CollisionFeature (planning/features/collision_feature.h) and its factory MakeCollisionFeature:
// FCL proximity pairs as per-link hinges.
#include "planning/features/collision_feature.h"

#include <stdexcept>
#include <vector>

namespace planning {
namespace {

// Per-evaluation buffers: the FCL workspace (its query counters are the feature's) and the pairs.
struct CollisionFeatureData : FeatureData {
  CollisionFeatureData(const Robot& robot, const Environment& env, const CollisionOptions& options)
      : coll(robot, env, options) {
    pairs.reserve(64);
  }
  CollisionData coll;
  std::vector<ProximityPair> pairs;
};

}  // namespace

std::unique_ptr<FeatureData> CollisionFeature::CreateData(const Robot& robot) const {
  return std::make_unique<CollisionFeatureData>(robot, *env_, options_);
}

long CollisionFeature::collision_queries(const FeatureData* data) const {
  return data == nullptr
             ? 0
             : static_cast<long>(static_cast<const CollisionFeatureData*>(data)->coll.queries);
}

long CollisionFeature::narrow_phase_calls(const FeatureData* data) const {
  return data == nullptr
             ? 0
             : static_cast<long>(
                   static_cast<const CollisionFeatureData*>(data)->coll.narrow_phase_calls);
}

QueryCounts CollisionFeature::query_counts(const FeatureData* data) const {
  return data == nullptr ? QueryCounts{}
                         : Counts(static_cast<const CollisionFeatureData*>(data)->coll);
}

void CollisionFeature::Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                            Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const {
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

std::unique_ptr<Feature> MakeCollisionFeature(const Robot& robot, const Environment& env,
                                              const CollisionOptions& options, double margin) {
  if (!(margin > 0.0)) throw std::invalid_argument("collision feature: margin must be > 0");
  return std::make_unique<CollisionFeature>(robot, env, options, margin);
}

}  // namespace planning
