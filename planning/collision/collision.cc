// The environment (placed objects) and the FCL scene of CollisionData: shapes built once per
// robot + environment, candidate pairs and broadphase managers (planning/collision/collision.h).
// The queries on the scene are in collision_queries.cc.
#include "planning/collision/collision.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

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

// Rows of the links that have collision shapes (FclScene::geo_row, −1 for the others) and their
// number (num_links); returns those links in link order.
std::vector<int> IndexShapeLinks(const Robot& robot, FclScene* scene) {
  FclScene& s = *scene;
  s.geo_row.assign(robot.links.size(), -1);
  std::vector<int> geo_links;  // links with collision shapes, in link order
  for (size_t l = 0; l < robot.links.size(); ++l) {
    if (robot.links[l].collisions.empty()) continue;
    s.geo_row[l] = static_cast<int>(geo_links.size());
    geo_links.push_back(static_cast<int>(l));
  }
  s.num_links = static_cast<int>(geo_links.size());
  return geo_links;
}

// One FCL object per collision geometry of the robot, in link order (meshes as convex hulls
// unless options.exact_meshes); poses are set per query.
void AddRobotShapes(const Robot& robot, const CollisionOptions& options, FclScene* scene) {
  FclScene& s = *scene;
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
}

// One FCL object per collision geometry of the environment's objects (each at its zero
// configuration), at its fixed world pose with its world AABB.
void AddEnvironmentShapes(const Environment& env, const CollisionOptions& options,
                          FclScene* scene) {
  FclScene& s = *scene;
  size_t count = 0;
  for (const PlacedObject& o : env.objects) {
    for (const Link& l : o.model.links) count += l.collisions.size();
  }
  s.env.resize(count);
  int k = 0;
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
}

// Self pairs that are never checked (FclScene::skip over the rows of `geo_links`): adjacent links
// and options.disabled_pairs.
void BuildSkipTable(const Robot& robot, const std::vector<int>& geo_links,
                    const CollisionOptions& options, FclScene* scene) {
  FclScene& s = *scene;
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
}

// Candidate shape pairs for distance queries: self pairs (a < b), then per object.
void BuildCandidatePairs(FclScene* scene) {
  FclScene& s = *scene;
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
  const std::vector<int> geo_links = IndexShapeLinks(robot, &s);
  AddRobotShapes(robot, options, &s);
  AddEnvironmentShapes(env, options, &s);
  BuildSkipTable(robot, geo_links, options, &s);
  BuildCandidatePairs(&s);
  // Broadphase managers.
  for (FclShape& shape : s.robot) s.robot_manager.registerObject(shape.obj.get());
  for (FclShape& shape : s.env) s.env_manager.registerObject(shape.obj.get());
  s.robot_manager.setup();
  s.env_manager.setup();
}

CollisionData::~CollisionData() = default;
CollisionData::CollisionData(CollisionData&&) noexcept = default;
CollisionData& CollisionData::operator=(CollisionData&&) noexcept = default;

}  // namespace planning
