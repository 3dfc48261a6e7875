// Collision and distance queries through FCL: shapes built once, transforms refreshed per query.
#include "planning/collision/collision.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>

#include "planning/collision/internal/fcl_scene.h"
#include "planning/robot/mesh_io.h"

namespace planning {
namespace {

using internal::FclPair;
using internal::FclScene;
using internal::FclShape;

// FCL convex shape of a hull (scaled per axis); null when the hull is empty.
std::shared_ptr<fcl::CollisionGeometryd> MakeConvex(const Mesh& hull,
                                                    const Eigen::Vector3d& scale) {
  if (hull.triangles.empty()) return nullptr;
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  vertices->reserve(hull.vertices.size());
  for (const Eigen::Vector3f& v : hull.vertices) {
    vertices->push_back(v.cast<double>().cwiseProduct(scale));
  }
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(4 * hull.triangles.size());
  for (const Eigen::Vector3i& t : hull.triangles) {
    faces->insert(faces->end(), {3, t[0], t[1], t[2]});
  }
  return std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.triangles.size()), faces);
}

// `hulls`: per mesh index of `model`, its convex hull (computed on first use) when meshes are
// collided as hulls; null for exact triangle BVHs.
std::shared_ptr<fcl::CollisionGeometryd> MakeGeometry(const Robot& model, const Geometry& g,
                                                      std::map<int, Mesh>* hulls = nullptr) {
  if (g.kind == Geometry::Kind::kMesh && hulls) {
    auto it = hulls->find(g.mesh);
    if (it == hulls->end()) it = hulls->emplace(g.mesh, ConvexHull(model.meshes.at(g.mesh))).first;
    if (auto convex = MakeConvex(it->second, g.size)) return convex;
  }
  switch (g.kind) {
    case Geometry::Kind::kBox:
      return std::make_shared<fcl::Boxd>(g.size[0], g.size[1], g.size[2]);
    case Geometry::Kind::kSphere:
      return std::make_shared<fcl::Sphered>(g.size[0]);
    case Geometry::Kind::kCylinder:
      return std::make_shared<fcl::Cylinderd>(g.size[0], g.size[1]);
    case Geometry::Kind::kCapsule:
      return std::make_shared<fcl::Capsuled>(g.size[0], g.size[1]);
    case Geometry::Kind::kMesh: {
      const Mesh& mesh = model.meshes.at(g.mesh);
      std::vector<fcl::Vector3d> points;
      points.reserve(mesh.vertices.size());
      for (const Eigen::Vector3f& v : mesh.vertices) {
        points.push_back(v.cast<double>().cwiseProduct(g.size));
      }
      std::vector<fcl::Triangle> tris;
      tris.reserve(mesh.triangles.size());
      for (const Eigen::Vector3i& t : mesh.triangles) tris.emplace_back(t[0], t[1], t[2]);
      auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
      bvh->beginModel(static_cast<int>(tris.size()), static_cast<int>(points.size()));
      bvh->addSubModel(points, tris);
      bvh->endModel();
      return bvh;
    }
  }
  throw std::logic_error("unknown geometry kind");
}

// Marks a capsule shape for the closed-form distance (if enabled).
void SetCapsule(const Geometry& g, const CollisionOptions& options, FclShape* shape) {
  if (!options.analytic_capsules || g.kind != Geometry::Kind::kCapsule) return;
  shape->capsule_radius = g.size[0];
  shape->capsule_half_length = 0.5 * g.size[1];
}

// The capsule along local z that contains a sphere, cylinder or capsule (FCL's shapes are centred
// and their axis is local z; a cylinder of radius r and height h lies inside the capsule of radius
// r around its axis segment of length h).
void SetBound(const Geometry& g, FclShape* shape) {
  switch (g.kind) {
    case Geometry::Kind::kSphere:
      shape->bound_radius = g.size[0];
      break;
    case Geometry::Kind::kCylinder:
    case Geometry::Kind::kCapsule:
      shape->bound_radius = g.size[0];
      shape->bound_half_length = 0.5 * g.size[1];
      break;
    default:
      break;
  }
}

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

// ---- Environment
// ---------------------------------------------------------------------------------

void AddObject(const Robot& object, const Eigen::Isometry3d& world_from_object,
               const std::string& name, Environment* env) {
  for (const PlacedObject& o : env->objects) {
    if (o.name == name)
      throw std::invalid_argument("AddObject: duplicate object name '" + name + "'");
  }
  env->objects.push_back({name, object, world_from_object});
}

Robot MakePrimitiveObject(const std::string& name, const Geometry& geometry) {
  if (geometry.kind == Geometry::Kind::kMesh) {
    throw std::invalid_argument("MakePrimitiveObject: '" + name + "' must be a primitive");
  }
  const bool round = geometry.kind != Geometry::Kind::kBox;  // size[0] is a radius
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(geometry.size[i]) || geometry.size[i] < 0 ||
        (round && i == 0 && !(geometry.size[0] > 0))) {
      throw std::invalid_argument("MakePrimitiveObject: '" + name +
                                  "': sizes must be finite and >= 0, radii > 0");
    }
  }
  Robot r;
  r.name = name;
  r.source = "<primitive " + name + ">";
  Link link;
  link.name = name;
  link.visuals.push_back(geometry);
  link.collisions.push_back(geometry);
  r.links.push_back(link);
  return r;
}

int FindObject(const Environment& env, const std::string& name) {
  for (size_t i = 0; i < env.objects.size(); ++i) {
    if (env.objects[i].name == name) return static_cast<int>(i);
  }
  throw std::invalid_argument("no object named '" + name + "' in the environment");
}

Eigen::Matrix3Xd ObjectChainPoints(const Environment& env, int object, int chain) {
  const PlacedObject& o = env.objects.at(object);
  KinematicsData kin(o.model);
  ForwardKinematics(o.model, Eigen::VectorXd::Zero(num_dofs(o.model)), &kin);
  Eigen::Matrix3Xd p;
  ChainPoints(o.model, kin, chain, &p);
  for (Eigen::Index k = 0; k < p.cols(); ++k) p.col(k) = o.world_from_object * p.col(k);
  return p;
}

// ---- CollisionData
// -------------------------------------------------------------------------------

CollisionData::CollisionData(const Robot& robot, const Environment& env,
                             const CollisionOptions& options)
    : scene(std::make_unique<internal::FclScene>()) {
  FclScene& s = *scene;
  s.self_collision = options.self_collision;
  s.environment = options.environment;
  s.geo_row.assign(robot.links.size(), -1);
  std::vector<int> geo_links;  // links with collision shapes, in link order
  for (size_t l = 0; l < robot.links.size(); ++l) {
    if (robot.links[l].collisions.empty()) continue;
    s.geo_row[l] = static_cast<int>(geo_links.size());
    geo_links.push_back(static_cast<int>(l));
  }
  s.num_links = static_cast<int>(geo_links.size());
  // Robot shapes.
  size_t count = 0;
  for (const Link& l : robot.links) count += l.collisions.size();
  s.robot.resize(count);
  int k = 0;
  std::map<int, Mesh> hulls;
  for (size_t l = 0; l < robot.links.size(); ++l) {
    for (const Geometry& g : robot.links[l].collisions) {
      FclShape& shape = s.robot[k];
      shape.link = static_cast<int>(l);
      shape.index = k++;
      shape.link_from_shape = g.link_from_geometry;
      shape.obj = std::make_unique<fcl::CollisionObjectd>(
          MakeGeometry(robot, g, options.exact_meshes ? nullptr : &hulls));
      shape.obj->setUserData(&shape);
      SetCapsule(g, options, &shape);
      SetBound(g, &shape);
    }
  }
  // Environment shapes at their fixed world poses.
  count = 0;
  for (const PlacedObject& o : env.objects) {
    for (const Link& l : o.model.links) count += l.collisions.size();
  }
  s.env.resize(count);
  k = 0;
  for (size_t i = 0; i < env.objects.size(); ++i) {
    const PlacedObject& o = env.objects[i];
    KinematicsData okin(o.model);
    ForwardKinematics(o.model, Eigen::VectorXd::Zero(num_dofs(o.model)), &okin);
    for (size_t l = 0; l < o.model.links.size(); ++l) {
      for (const Geometry& g : o.model.links[l].collisions) {
        FclShape& shape = s.env[k];
        shape.link = static_cast<int>(l);
        shape.object = static_cast<int>(i);
        shape.index = k++;
        shape.link_from_shape = g.link_from_geometry;
        shape.obj = std::make_unique<fcl::CollisionObjectd>(MakeGeometry(o.model, g));
        shape.obj->setTransform(o.world_from_object * okin.world_from_link[l] *
                                g.link_from_geometry);
        shape.obj->computeAABB();
        shape.obj->setUserData(&shape);
        SetCapsule(g, options, &shape);
        SetBound(g, &shape);
      }
    }
  }
  // Self pairs that are never checked.
  s.skip.assign(static_cast<size_t>(s.num_links) * s.num_links, 0);
  for (int a = 0; a < s.num_links; ++a) {
    for (int b = 0; b < s.num_links; ++b) {
      if (AreAdjacent(robot, geo_links[a], geo_links[b])) s.skip[a * s.num_links + b] = 1;
    }
  }
  for (const auto& [na, nb] : options.disabled_pairs) {
    const int a = s.geo_row[FindLink(robot, na)], b = s.geo_row[FindLink(robot, nb)];
    if (a < 0 || b < 0) continue;  // a link without shapes is never checked anyway
    s.skip[a * s.num_links + b] = s.skip[b * s.num_links + a] = 1;
  }
  // Candidate shape pairs for distance queries: self pairs (a < b), then per object.
  if (s.self_collision) {
    for (size_t a = 0; a < s.robot.size(); ++a) {
      for (size_t b = a + 1; b < s.robot.size(); ++b) {
        if (s.skip[s.geo_row[s.robot[a].link] * s.num_links + s.geo_row[s.robot[b].link]]) {
          continue;
        }
        s.pairs.push_back({static_cast<int>(a), static_cast<int>(b), false});
      }
    }
  }
  if (s.environment) {
    for (size_t e = 0; e < s.env.size(); ++e) {
      for (size_t a = 0; a < s.robot.size(); ++a) {
        s.pairs.push_back({static_cast<int>(a), static_cast<int>(e), true});
      }
    }
    std::stable_sort(s.pairs.begin(), s.pairs.end(), [&](const FclPair& x, const FclPair& y) {
      const int ox = x.env_pair ? s.env[x.b].object : -1;
      const int oy = y.env_pair ? s.env[y.b].object : -1;
      return ox < oy;
    });
  }
  // Broadphase managers.
  for (FclShape& shape : s.robot) s.robot_manager.registerObject(shape.obj.get());
  for (FclShape& shape : s.env) s.env_manager.registerObject(shape.obj.get());
  s.robot_manager.setup();
  s.env_manager.setup();
}

CollisionData::~CollisionData() = default;
CollisionData::CollisionData(CollisionData&&) noexcept = default;
CollisionData& CollisionData::operator=(CollisionData&&) noexcept = default;

// ---- Queries
// -------------------------------------------------------------------------------------

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
