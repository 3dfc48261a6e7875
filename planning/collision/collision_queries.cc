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
  std::vector<ProximityPair>* all = nullptr;        // CheckCollisions: every colliding pair
  std::vector<ProximityPair>* hull_only = nullptr;  // hull hits the exact meshes refute
  int max_pairs = 1;
};

// Self pairs of the same rigid body or of a body and its collision parent (adjacent), and
// disabled pairs, are never checked. O(1).
bool SkipSelf(const FclScene& s, int link_a, int link_b) {
  const int a = s.body[link_a], b = s.body[link_b];
  if (a == b || s.parent_body[a] == b || s.parent_body[b] == a) return true;
  return !s.disabled.empty() && s.disabled.count(internal::PairKey(link_a, link_b)) > 0;
}

bool Skip(const FclScene& s, const FclShape& a, const FclShape& b) {
  if (a.object >= 0 && b.object >= 0) return true;  // environment vs environment
  if (a.object < 0 && b.object < 0) {
    if (!s.skip_self.empty()) return s.skip_self[a.index * s.robot.size() + b.index] != 0;
    return !s.self_collision || SkipSelf(s, a.link, b.link);
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
  // Two capsules (analytic_capsules) or two spheres (capsules of length 0); a sphere against a
  // capsule goes through FCL, as before spheres were closed form.
  return a.capsule_radius > 0.0 && b.capsule_radius > 0.0 &&
         (a.capsule_half_length > 0.0) == (b.capsule_half_length > 0.0);
}

// Capsule pairs in closed form are as cheap as their bounding-capsule test: not pre-checked.
bool ClosedFormCapsules(const FclShape& a, const FclShape& b) {
  return ClosedFormPair(a, b) && a.capsule_half_length > 0.0;
}

// Distance between the bounding capsules of a and b (≤ their true distance); 0 when either has
// none.
double BoundGap(const FclShape& a, const FclShape& b) {
  if (a.bound_radius <= 0.0 || b.bound_radius <= 0.0) return 0.0;
  Eigen::Vector3d p, q;  // the segments' ends as Place computed them from the poses
  ClosestSegmentPoints(a.bound_start, a.bound_span, b.bound_start, b.bound_span, &p, &q);
  return (p - q).norm() - a.bound_radius - b.bound_radius;
}

enum class PairVerdict { kFree, kCollision, kHullOnly };

// A yes/no narrow phase (FCL collide with its default request: one contact, no penetration depth,
// so libccd answers by MPR intersection and no EPA runs). A hit of a mesh's convex hull is then
// confirmed on the exact triangles (OBBRSS BVH against the other shape, or its exact mesh).
PairVerdict CollidePair(const FclScene& s, const FclShape& a, const FclShape& b,
                        CollisionData* coll) {
  const auto collide = [coll](const fcl::CollisionObjectd* x, const fcl::CollisionObjectd* y) {
    ++coll->narrow_phase_calls;
    ++coll->bool_pair_tests;
    try {
      fcl::CollisionRequestd request;
      fcl::CollisionResultd result;
      return fcl::collide(x, y, request, result) > 0;
    } catch (const std::exception&) {
      return true;  // libccd failures on touching shapes: be conservative
    }
  };
  if (!collide(a.obj.get(), b.obj.get())) return PairVerdict::kFree;
  if (!s.confirm_meshes || (!a.exact && !b.exact)) return PairVerdict::kCollision;
  const fcl::CollisionObjectd* ea = a.obj.get();
  const fcl::CollisionObjectd* eb = b.obj.get();
  if (a.exact) {
    a.exact->setTransform(a.obj->getTransform());
    a.exact->computeAABB();
    ea = a.exact.get();
  }
  if (b.exact) {
    b.exact->setTransform(b.obj->getTransform());
    b.exact->computeAABB();
    eb = b.exact.get();
  }
  return collide(ea, eb) ? PairVerdict::kCollision : PairVerdict::kHullOnly;
}

// Broadphase callback: filter, count, narrow phase; returns true (stop) at the first hit (or, for
// CheckCollisions, when max_pairs are found).
bool CollideCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto* q = static_cast<BroadphaseQuery*>(data);
  const FclShape* a = ShapeOf(o1);
  const FclShape* b = ShapeOf(o2);
  if (Skip(*q->scene, *a, *b)) return false;
  if (a->object >= 0) std::swap(a, b);                      // robot shape first
  if (b->object < 0 && b->link < a->link) std::swap(a, b);  // self pairs: lower link first
  if (BoundGap(*a, *b) > 0.0) return false;                 // bounding capsules apart: no contact
  const PairVerdict verdict = CollidePair(*q->scene, *a, *b, q->coll);
  if (verdict == PairVerdict::kFree) return false;
  ProximityPair pair;
  pair.link_a = a->link;
  pair.link_b = b->object >= 0 ? -1 : b->link;
  pair.object = b->object;
  if (verdict == PairVerdict::kHullOnly) {
    if (q->hull_only) q->hull_only->push_back(pair);
    return false;  // not a collision: go on
  }
  q->hit = true;
  q->pair = pair;
  if (q->all) {  // CheckCollisions: every colliding pair (up to its limit)
    q->all->push_back(pair);
    return static_cast<int>(q->all->size()) >= q->max_pairs;
  }
  return true;
}

// Moves the robot's shapes to `kin` (transforms and world AABBs); the broadphase tree is refreshed
// only for boolean checks (`broadphase`), distance queries test the boxes pair by pair.
void UpdateRobot(const KinematicsData& kin, FclScene* s, bool broadphase) {
  for (FclShape& shape : s->robot) {
    internal::Place(&shape, kin.world_from_link[shape.link] * shape.link_from_shape);
  }
  if (broadphase) s->robot_manager.update();
}

// Signed distance of two capsules (core segments along their local z, FclShape radius and half
// length) in closed form: |P − Q| − r_a − r_b with P, Q the closest points of the core segments.
// The normal is (P − Q)/|P − Q| (from b to a); when the segments meet it is u × v, or a vector
// perpendicular to a's axis for parallel ones. Witness points lie on the two surfaces along the
// normal; a penetrating pair reports the middle of its two surface points as both witnesses.
void CapsuleDistance(const FclShape& a, const FclShape& b, ProximityPair* out) {
  const Eigen::Vector3d& ua = a.axis;
  const Eigen::Vector3d& ub = b.axis;
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
  ++coll->distance_pair_tests;
  if (ClosedFormPair(a, b)) {
    CapsuleDistance(a, b, out);
    return;
  }
  // Signed distance (penetration by EPA) only between convex shapes; for a triangle BVH it would
  // run EPA on every overlapping triangle. A BVH pair in contact takes the contact branch below.
  const bool bvh = a.obj->collisionGeometry()->getObjectType() == fcl::OT_BVH ||
                   b.obj->collisionGeometry()->getObjectType() == fcl::OT_BVH;
  fcl::DistanceRequestd request(true, !bvh);
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
  ++coll->distance_pair_tests;
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

// A candidate shape pair of the distance queries, with the order key of the checked-pair order
// (self pairs (a, b) with a < b first, then per object its shapes e, each against the robot's
// shapes a): the order in which pairs are visited and ties are broken.
struct Candidate {
  int a = 0;  // robot shape
  int b = 0;  // robot shape (self) or env shape
  bool env = false;
  int object = -1;
  double gap = 0.0;  // AABB gap [m]
  bool operator<(const Candidate& o) const {
    return std::make_tuple(env, object, env ? b : a, env ? a : b) <
           std::make_tuple(o.env, o.object, o.env ? o.b : o.a, o.env ? o.a : o.b);
  }
};

// Every checked shape pair whose world AABBs are at most `margin` apart (gap <= margin), by a
// sweep over the boxes sorted along x: O(n log n + pairs found), never the n² pair list. Pairs
// never checked (environment against environment, adjacent or disabled self pairs) are left out.
void CollectCandidates(const FclScene& s, double margin, std::vector<Candidate>* out) {
  out->clear();
  struct Box {
    double min_x, max_x;
    int shape;  // >= 0 robot shape, < 0: env shape −1 − index
  };
  std::vector<Box> boxes;
  boxes.reserve(s.robot.size() + (s.environment ? s.env.size() : 0));
  for (const FclShape& r : s.robot) {
    boxes.push_back({r.obj->getAABB().min_[0], r.obj->getAABB().max_[0], r.index});
  }
  if (s.environment) {
    for (const FclShape& e : s.env) {
      boxes.push_back({e.obj->getAABB().min_[0], e.obj->getAABB().max_[0], -1 - e.index});
    }
  }
  std::sort(boxes.begin(), boxes.end(), [](const Box& x, const Box& y) {
    return std::tie(x.min_x, x.shape) < std::tie(y.min_x, y.shape);
  });
  std::vector<int> active;  // indices into boxes whose max_x + margin reaches the sweep
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Box& bi = boxes[i];
    size_t keep = 0;
    for (int k : active) {
      if (boxes[k].max_x + margin >= bi.min_x) active[keep++] = k;
    }
    active.resize(keep);
    for (int k : active) {
      const Box& bk = boxes[k];
      if (bi.shape < 0 && bk.shape < 0) continue;  // environment vs environment
      const bool env = bi.shape < 0 || bk.shape < 0;
      if (!env && !s.self_collision) continue;
      const FclShape& a =
          env ? s.robot[std::max(bi.shape, bk.shape)] : s.robot[std::min(bi.shape, bk.shape)];
      const FclShape& b =
          env ? s.env[-1 - std::min(bi.shape, bk.shape)] : s.robot[std::max(bi.shape, bk.shape)];
      if (Skip(s, a, b)) continue;
      const double gap = AabbGap(*a.obj, *b.obj);
      if (gap > margin) continue;
      out->push_back({a.index, b.index, env, env ? b.object : -1, gap});
    }
    active.push_back(static_cast<int>(i));
  }
}

template <typename Visit>
void ForEachClosePair(const Robot& robot, const KinematicsData& kin, double margin,
                      CollisionData* coll, Visit&& visit) {
  FclScene& s = *coll->scene;
  assert(kin.world_from_link.size() == robot.links.size());
  (void)robot;
  UpdateRobot(kin, &s, false);
  ++coll->queries;
  std::vector<Candidate> candidates;
  CollectCandidates(s, margin, &candidates);
  std::sort(candidates.begin(), candidates.end());  // the checked-pair order
  for (const Candidate& c : candidates) {
    const FclShape& a = s.robot[c.a];
    const FclShape& b = c.env ? s.env[c.b] : s.robot[c.b];
    if (!AabbGapBelow(*a.obj, *b.obj, margin)) continue;
    // Closed-form capsule pairs are as cheap as their bound; others skip the narrow phase when
    // their bounding capsules are margin apart.
    if (!ClosedFormCapsules(a, b) && BoundGap(a, b) >= margin) continue;
    ProximityPair pair;
    pair.link_a = a.link;
    pair.link_b = c.env ? -1 : b.link;
    pair.object = c.env ? b.object : -1;
    ShapeDistance(a, b, coll, &pair);
    visit(pair);
  }
}

// The diagonal of the box around every shape (robot and environment): no pair's AABB gap exceeds
// it.
double SceneDiagonal(const FclScene& s) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto* shapes : {&s.robot, &s.env}) {
    for (const FclShape& x : *shapes) {
      lo = lo.cwiseMin(x.obj->getAABB().min_);
      hi = hi.cwiseMax(x.obj->getAABB().max_);
    }
  }
  return (hi - lo).allFinite() ? (hi - lo).norm() : 0.0;
}

}  // namespace

void internal::BuildSkipTable(FclScene* scene) {
  FclScene& s = *scene;
  const size_t n = s.robot.size();
  s.skip_self.clear();
  if (n > FclScene::kMaxSkipTableShapes) return;
  s.skip_self.resize(n * n);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) {
      s.skip_self[i * n + j] = !s.self_collision || SkipSelf(s, s.robot[i].link, s.robot[j].link);
    }
  }
}

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

CollisionReport CheckCollisions(const Robot& robot, const KinematicsData& kin, CollisionData* coll,
                                int max_pairs) {
  FclScene& s = *coll->scene;
  assert(kin.world_from_link.size() == robot.links.size());
  (void)robot;
  UpdateRobot(kin, &s, true);
  ++coll->queries;
  CollisionReport report;
  BroadphaseQuery q{&s, coll, false, {}};
  q.all = &report.pairs;
  q.hull_only = &report.hull_only;
  q.max_pairs = std::max(1, max_pairs);
  if (s.environment && !s.env.empty()) s.robot_manager.collide(&s.env_manager, &q, CollideCallback);
  if (static_cast<int>(report.pairs.size()) < q.max_pairs && s.self_collision) {
    s.robot_manager.collide(&q, CollideCallback);
  }
  const auto order = [](const ProximityPair& x, const ProximityPair& y) {
    return std::tie(x.object, x.link_a, x.link_b) < std::tie(y.object, y.link_a, y.link_b);
  };
  std::sort(report.pairs.begin(), report.pairs.end(), order);
  std::sort(report.hull_only.begin(), report.hull_only.end(), order);
  report.in_collision = !report.pairs.empty();
  return report;
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
  // pair that comes first in the checked-pair order. The pairs are collected in growing gap
  // windows (0.05 m, then ×4) by the sweep, never all n² of them: a window's pairs follow those
  // of the windows before it in the same global (gap, order) sequence.
  double best = std::numeric_limits<double>::infinity();
  Candidate best_pair;
  bool have_best = false;
  const double diagonal = SceneDiagonal(s);
  std::vector<Candidate> candidates;
  double done_up_to = -1.0;  // every pair with gap <= this has been considered
  for (double window = 0.05;; window *= 4.0) {
    CollectCandidates(s, window, &candidates);
    std::erase_if(candidates, [&](const Candidate& c) { return c.gap <= done_up_to; });
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
      if (x.gap != y.gap) return x.gap < y.gap;
      return x < y;
    });
    bool stopped = false;
    for (const Candidate& c : candidates) {
      // A pair's distance is at least its gap, and penetration (< 0) only happens at gap 0: while
      // the best is negative every overlapping pair is still a candidate for the deepest.
      if (c.gap > std::max(best, 0.0)) {
        stopped = true;
        break;
      }
      const FclShape& a = s.robot[c.a];
      const FclShape& b = c.env ? s.env[c.b] : s.robot[c.b];
      ProximityPair pair;
      pair.link_a = a.link;
      pair.link_b = c.env ? -1 : b.link;
      pair.object = c.env ? b.object : -1;
      ShapeDistance(a, b, coll, &pair);
      if (pair.distance < best || (pair.distance == best && have_best && c < best_pair)) {
        best = pair.distance;
        best_pair = c;
        have_best = true;
        if (closest) *closest = pair;
      }
    }
    done_up_to = window;
    if (stopped || std::max(best, 0.0) <= window || window > diagonal) break;
  }
  return best;
}

}  // namespace planning
