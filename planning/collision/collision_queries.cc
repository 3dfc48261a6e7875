// Collision and distance queries through FCL (planning/collision/collision.h): InCollision,
// ComputeProximity and MinDistance on the scene CollisionData built (collision.cc), with the
// broadphase callback, the bounding-capsule filter and the closed-form capsule distance.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/collision/internal/fcl_scene.h"

namespace planning {
namespace {

using internal::FclPair;
using internal::FclScene;
using internal::FclShape;

// Shape pointer stored as FCL user data.
const FclShape* ShapeOf(const fcl::CollisionObjectd* o) {
  return static_cast<const FclShape*>(o->getUserData());
}

struct BroadphaseQuery {
  const FclScene* scene;
  CollisionData* coll;
  bool hit = false;
  ProximityPair pair;
};

bool Skip(const FclScene& s, const FclShape& a, const FclShape& b) {
  if (a.object >= 0 && b.object >= 0) return true;  // environment vs environment
  if (a.object < 0 && b.object < 0) {
    return !s.self_collision || s.skip[s.geo_row[a.link] * s.num_links + s.geo_row[b.link]] != 0;
  }
  return !s.environment;
}

// Closest points P = a0 + s·u and Q = b0 + t·v (s, t ∈ [0, 1]) of the segments a0 + [0, 1]·u and
// b0 + [0, 1]·v: minimises |P − Q|² = |w + s·u − t·v|² with w = a0 − b0, whose stationary point
// solves [u·u, −u·v; −u·v, v·v] (s, t) = (−u·w, v·w); the clamped solution is found by fixing s,
// clamping t, and re-solving s for the clamped t. Parallel segments (the 2 × 2 system is
// singular) take the middle of their overlap, so the witness points move continuously with the
// pose; point-like segments (length² ≤ 1e-24) are handled as points.
void ClosestSegmentPoints(const Eigen::Vector3d& a0, const Eigen::Vector3d& u,
                          const Eigen::Vector3d& b0, const Eigen::Vector3d& v, Eigen::Vector3d* p,
                          Eigen::Vector3d* q) {
  constexpr double kTiny = 1e-24;
  const Eigen::Vector3d w = a0 - b0;
  const double uu = u.squaredNorm(), vv = v.squaredNorm(), uv = u.dot(v);
  const double uw = u.dot(w), vw = v.dot(w);
  const auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
  double s = 0.0, t = 0.0;
  if (uu <= kTiny && vv <= kTiny) {
    // Two points.
  } else if (uu <= kTiny) {
    t = clamp01(vw / vv);
  } else if (vv <= kTiny) {
    s = clamp01(-uw / uu);
  } else {
    const double det = uu * vv - uv * uv;  // = |u × v|² ≥ 0
    if (det > 1e-12 * uu * vv) {
      s = clamp01((uv * vw - vv * uw) / det);
    } else {
      // Parallel: b0 and b0 + v project to s0, s1 on a's line; take the middle of the overlap
      // of [s0, s1] with [0, 1], or the nearer end of a when they do not overlap.
      const double s0 = -uw / uu, s1 = (uv - uw) / uu;
      const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(1.0, std::max(s0, s1));
      s = lo <= hi ? 0.5 * (lo + hi) : (std::max(s0, s1) < 0.0 ? 0.0 : 1.0);
    }
    t = (uv * s + vw) / vv;
    if (t < 0.0 || t > 1.0) {
      t = clamp01(t);
      s = clamp01((uv * t - uw) / uu);
    }
  }
  *p = a0 + s * u;
  *q = b0 + t * v;
}

// Both shapes are capsules answered in closed form (CollisionOptions::analytic_capsules).
bool ClosedFormPair(const FclShape& a, const FclShape& b) {
  return a.capsule_radius > 0.0 && b.capsule_radius > 0.0;
}

// Distance between the bounding capsules of a and b (≤ their true distance); 0 when either has
// none.
double BoundGap(const FclShape& a, const FclShape& b) {
  if (a.bound_radius <= 0.0 || b.bound_radius <= 0.0) return 0.0;
  const Eigen::Vector3d ua = a.obj->getRotation().col(2), ub = b.obj->getRotation().col(2);
  Eigen::Vector3d p, q;
  ClosestSegmentPoints(
      a.obj->getTranslation() - a.bound_half_length * ua, 2.0 * a.bound_half_length * ua,
      b.obj->getTranslation() - b.bound_half_length * ub, 2.0 * b.bound_half_length * ub, &p, &q);
  return (p - q).norm() - a.bound_radius - b.bound_radius;
}

// Broadphase callback: filter, count, narrow phase; returns true (stop) at the first hit.
bool CollideCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto* q = static_cast<BroadphaseQuery*>(data);
  const FclShape* a = ShapeOf(o1);
  const FclShape* b = ShapeOf(o2);
  if (Skip(*q->scene, *a, *b)) return false;
  if (a->object >= 0) std::swap(a, b);       // robot shape first
  if (BoundGap(*a, *b) > 0.0) return false;  // bounding capsules apart: no contact
  ++q->coll->narrow_phase_calls;
  bool hit = false;
  try {
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    hit = fcl::collide(a->obj.get(), b->obj.get(), request, result) > 0;
  } catch (const std::exception&) {
    hit = true;  // libccd failures on touching shapes: be conservative
  }
  if (hit) {
    q->hit = true;
    q->pair.link_a = a->link;
    q->pair.link_b = b->object >= 0 ? -1 : b->link;
    q->pair.object = b->object;
  }
  return hit;
}

// Moves the robot's shapes to `kin` (transforms and world AABBs); the broadphase tree is refreshed
// only for boolean checks (`broadphase`), distance queries test the boxes pair by pair.
void UpdateRobot(const KinematicsData& kin, FclScene* s, bool broadphase) {
  for (FclShape& shape : s->robot) {
    shape.obj->setTransform(kin.world_from_link[shape.link] * shape.link_from_shape);
    shape.obj->computeAABB();
  }
  if (broadphase) s->robot_manager.update();
}

// Signed distance of two capsules (core segments along their local z, FclShape radius and half
// length) in closed form: |P − Q| − r_a − r_b with P, Q the closest points of the core segments.
// The normal is (P − Q)/|P − Q| (from b to a); when the segments meet it is u × v, or a vector
// perpendicular to a's axis for parallel ones. Witness points lie on the two surfaces along the
// normal; a penetrating pair reports the middle of its two surface points as both witnesses.
void CapsuleDistance(const FclShape& a, const FclShape& b, ProximityPair* out) {
  const Eigen::Vector3d ua = a.obj->getRotation().col(2), ub = b.obj->getRotation().col(2);
  const Eigen::Vector3d a0 = a.obj->getTranslation() - a.capsule_half_length * ua;
  const Eigen::Vector3d b0 = b.obj->getTranslation() - b.capsule_half_length * ub;
  const Eigen::Vector3d u = 2.0 * a.capsule_half_length * ua;
  const Eigen::Vector3d v = 2.0 * b.capsule_half_length * ub;
  Eigen::Vector3d p, q;
  ClosestSegmentPoints(a0, u, b0, v, &p, &q);
  const Eigen::Vector3d diff = p - q;
  const double len = diff.norm();
  Eigen::Vector3d n;
  if (len > 1e-12) {
    n = diff / len;
  } else {
    n = ua.cross(ub);
    if (n.norm() < 1e-9) n = ua.unitOrthogonal();
    n.normalize();
  }
  out->distance = len - a.capsule_radius - b.capsule_radius;
  out->normal = n;
  out->point_a = p - a.capsule_radius * n;
  out->point_b = q + b.capsule_radius * n;
  if (out->distance < 0.0) out->point_a = out->point_b = 0.5 * (out->point_a + out->point_b);
}

// Signed distance between two shapes with witness points and the normal from b to a.
void ShapeDistance(const FclShape& a, const FclShape& b, CollisionData* coll, ProximityPair* out) {
  ++coll->narrow_phase_calls;
  if (ClosedFormPair(a, b)) {
    CapsuleDistance(a, b, out);
    return;
  }
  fcl::DistanceRequestd request(true, true);
  fcl::DistanceResultd result;
  double d = 0.0;
  bool ok = true;
  try {
    d = fcl::distance(a.obj.get(), b.obj.get(), request, result);
  } catch (const std::exception&) {
    ok = false;
  }
  if (ok && d > 1e-9) {
    out->distance = d;
    out->point_a = result.nearest_points[0];
    out->point_b = result.nearest_points[1];
    const Eigen::Vector3d diff = out->point_a - out->point_b;
    const double len = diff.norm();
    if (len > 1e-12) {
      out->normal = diff / len;
    } else {
      const Eigen::Vector3d c = a.obj->getTranslation() - b.obj->getTranslation();
      out->normal = c.norm() > 1e-12 ? Eigen::Vector3d(c.normalized()) : Eigen::Vector3d::UnitZ();
    }
    return;
  }
  // In contact (or the distance solver failed): penetration depth and normal from the contact.
  ++coll->narrow_phase_calls;
  fcl::CollisionRequestd creq(1, true);
  fcl::CollisionResultd cres;
  bool contact = false;
  try {
    contact = fcl::collide(a.obj.get(), b.obj.get(), creq, cres) > 0;
  } catch (const std::exception&) {
    contact = false;
  }
  if (contact) {
    const fcl::Contactd& c = cres.getContact(0);
    // FCL's normal points from o1 (= a) to o2 (= b); ours points from b to a.
    const bool swapped = c.o1 != a.obj->collisionGeometry().get();
    Eigen::Vector3d n = swapped ? Eigen::Vector3d(c.normal) : Eigen::Vector3d(-c.normal);
    if (!(n.norm() > 1e-12)) n = Eigen::Vector3d::UnitZ();
    out->distance = -std::abs(c.penetration_depth);
    out->point_a = c.pos;
    out->point_b = c.pos;
    out->normal = n.normalized();
  } else {
    // Touching: distance 0 at the reported points.
    out->distance = ok ? std::max(d, 0.0) : 0.0;
    out->point_a = result.nearest_points[0];
    out->point_b = result.nearest_points[1];
    const Eigen::Vector3d c = a.obj->getTranslation() - b.obj->getTranslation();
    out->normal = c.norm() > 1e-12 ? Eigen::Vector3d(c.normalized()) : Eigen::Vector3d::UnitZ();
  }
}

// Per-axis gap between the world AABBs of two objects (0 on the axes where they overlap).
Eigen::Vector3d AabbGapVector(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b) {
  const fcl::AABBd& x = a.getAABB();
  const fcl::AABBd& y = b.getAABB();
  return (x.min_ - y.max_).cwiseMax(y.min_ - x.max_).cwiseMax(Eigen::Vector3d::Zero());
}

// Distance between the world AABBs of two objects (0 if they overlap).
double AabbGap(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b) {
  return AabbGapVector(a, b).norm();
}

// AabbGap(a, b) < margin without the square root (margin >= 0).
bool AabbGapBelow(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b, double margin) {
  return AabbGapVector(a, b).squaredNorm() < margin * margin;
}

template <typename Visit>
void ForEachClosePair(const Robot& robot, const KinematicsData& kin, double margin,
                      CollisionData* coll, Visit&& visit) {
  FclScene& s = *coll->scene;
  assert(kin.world_from_link.size() == robot.links.size());
  (void)robot;
  UpdateRobot(kin, &s, false);
  ++coll->queries;
  for (const FclPair& p : s.pairs) {
    const FclShape& a = s.robot[p.a];
    const FclShape& b = p.env_pair ? s.env[p.b] : s.robot[p.b];
    if (!AabbGapBelow(*a.obj, *b.obj, margin)) continue;
    // Closed-form capsule pairs are as cheap as their bound; others skip the narrow phase when
    // their bounding capsules are margin apart.
    if (!ClosedFormPair(a, b) && BoundGap(a, b) >= margin) continue;
    ProximityPair pair;
    pair.link_a = a.link;
    pair.link_b = p.env_pair ? -1 : b.link;
    pair.object = p.env_pair ? b.object : -1;
    ShapeDistance(a, b, coll, &pair);
    visit(pair);
  }
}
}  // namespace

bool InCollision(const Robot& robot, const KinematicsData& kin, CollisionData* coll,
                 ProximityPair* hit) {
  FclScene& s = *coll->scene;
  assert(kin.world_from_link.size() == robot.links.size());
  (void)robot;
  UpdateRobot(kin, &s, true);
  ++coll->queries;
  BroadphaseQuery q{&s, coll, false, {}};
  if (s.environment && !s.env.empty()) s.robot_manager.collide(&s.env_manager, &q, CollideCallback);
  if (!q.hit && s.self_collision) s.robot_manager.collide(&q, CollideCallback);
  if (q.hit && hit) *hit = q.pair;
  return q.hit;
}

void ComputeProximity(const Robot& robot, const KinematicsData& kin, double margin,
                      CollisionData* coll, std::vector<ProximityPair>* out) {
  if (!(margin >= 0)) throw std::invalid_argument("ComputeProximity: margin must be >= 0");
  out->clear();
  ForEachClosePair(robot, kin, margin, coll, [&](const ProximityPair& p) {
    if (p.distance >= margin) return;
    // Pairs arrive grouped by (object, link_a, link_b) shape order; keep the closest per link pair.
    for (ProximityPair& existing : *out) {
      if (existing.link_a == p.link_a && existing.link_b == p.link_b &&
          existing.object == p.object) {
        if (p.distance < existing.distance) existing = p;
        return;
      }
    }
    out->push_back(p);
  });
  std::sort(out->begin(), out->end(), [](const ProximityPair& x, const ProximityPair& y) {
    return std::tie(x.object, x.link_a, x.link_b) < std::tie(y.object, y.link_a, y.link_b);
  });
}

double MinDistance(const Robot& robot, const KinematicsData& kin, CollisionData* coll,
                   ProximityPair* closest) {
  FclScene& s = *coll->scene;
  assert(kin.world_from_link.size() == robot.links.size());
  (void)robot;
  UpdateRobot(kin, &s, false);
  ++coll->queries;
  // Branch and bound: a pair's distance is at least the gap between its bounding boxes, so pairs
  // are visited by increasing gap until the gap reaches the best distance found. Ties keep the
  // pair that comes first in the checked-pair order.
  std::vector<std::pair<double, int>>& order = s.order;
  order.clear();
  for (size_t i = 0; i < s.pairs.size(); ++i) {
    const FclPair& p = s.pairs[i];
    const FclShape& b = p.env_pair ? s.env[p.b] : s.robot[p.b];
    order.emplace_back(AabbGap(*s.robot[p.a].obj, *b.obj), static_cast<int>(i));
  }
  std::sort(order.begin(), order.end());
  double best = std::numeric_limits<double>::infinity();
  int best_index = -1;
  for (const auto& [gap, i] : order) {
    // A pair's distance is at least its gap, and penetration (< 0) only happens at gap 0: while
    // the best is negative every overlapping pair is still a candidate for the deepest.
    if (gap > std::max(best, 0.0)) break;
    const FclPair& p = s.pairs[i];
    const FclShape& a = s.robot[p.a];
    const FclShape& b = p.env_pair ? s.env[p.b] : s.robot[p.b];
    ProximityPair pair;
    pair.link_a = a.link;
    pair.link_b = p.env_pair ? -1 : b.link;
    pair.object = p.env_pair ? b.object : -1;
    ShapeDistance(a, b, coll, &pair);
    if (pair.distance < best || (pair.distance == best && i < best_index)) {
      best = pair.distance;
      best_index = i;
      if (closest) *closest = pair;
    }
  }
  return best;
}

}  // namespace planning
