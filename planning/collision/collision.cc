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
  // A sphere is a capsule of length 0: sphere–sphere distances are always closed form (libccd's
  // EPA converges slowly on round shapes and stops short of the exact depth).
  if (g.kind == Geometry::Kind::kSphere) {
    shape->capsule_radius = g.size[0];
    shape->capsule_half_length = 0.0;
    return;
  }
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

// FclScene::body and parent_body in O(n): each link's rigid body (following fixed joints up) and
// each body's nearest ancestor body with collision geometry, memoised in one pass over the links
// (a link's parent is resolved before the link through an explicit stack, whatever their order).
void BuildAdjacency(const Robot& robot, FclScene* scene) {
  const int n = static_cast<int>(robot.links.size());
  std::vector<int>& body = scene->body;
  body.assign(n, -1);
  std::vector<int> stack;
  for (int l = 0; l < n; ++l) {
    for (int k = l; body[k] < 0;) {  // walk up until a resolved link or a body root
      const int j = robot.links[k].parent_joint;
      if (j < 0 || robot.joints[j].type != JointType::kFixed) {
        body[k] = k;
        break;
      }
      stack.push_back(k);
      k = robot.joints[j].parent_link;
    }
    while (!stack.empty()) {  // everything on the way hangs from the same body
      const int k = stack.back();
      stack.pop_back();
      body[k] = body[robot.joints[robot.links[k].parent_joint].parent_link];
    }
  }
  std::vector<char> has_collision(n, 0);
  for (int l = 0; l < n; ++l) {
    if (!robot.links[l].collisions.empty()) has_collision[body[l]] = 1;
  }
  // parent_body[b]: the body above b's parent joint if it has collision geometry, else its own
  // parent_body (geometry-free frames such as the middle link of a 2-DOF joint are skipped).
  std::vector<int>& parent = scene->parent_body;
  parent.assign(n, -2);  // −2: not computed yet
  for (int l = 0; l < n; ++l) {
    for (int b = body[l]; parent[b] == -2;) {
      const int j = robot.links[b].parent_joint;
      if (j < 0) {
        parent[b] = -1;
        break;
      }
      const int up = body[robot.joints[j].parent_link];
      if (has_collision[up]) {
        parent[b] = up;
        break;
      }
      if (parent[up] == -2) {
        stack.push_back(b);
        b = up;
        continue;
      }
      parent[b] = parent[up];
    }
    while (!stack.empty()) {
      const int b = stack.back();
      stack.pop_back();
      parent[b] = parent[body[robot.joints[robot.links[b].parent_joint].parent_link]];
    }
  }
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
      // A mesh collided as its hull keeps its exact triangles for confirming hull hits.
      if (g.kind == Geometry::Kind::kMesh && !options.exact_meshes && options.confirm_meshes &&
          shape.obj->collisionGeometry()->getNodeType() == fcl::GEOM_CONVEX) {
        shape.exact = std::make_unique<fcl::CollisionObjectd>(MakeGeometry(robot, g));
      }
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
        shape.obj->setUserData(&shape);
        SetCapsule(g, options, &shape);
        SetBound(g, &shape);
        internal::Place(&shape,
                        o.world_from_object * okin.world_from_link[l] * g.link_from_geometry);
      }
    }
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

std::string PairName(const Robot& robot, const Environment& env, const ProximityPair& pair) {
  if (pair.link_a < 0) return "";
  std::string name = robot.links[pair.link_a].name;
  if (pair.object >= 0) {
    return name.append(" vs object '").append(env.objects[pair.object].name).append("'");
  }
  if (pair.link_b >= 0) name.append(" vs ").append(robot.links[pair.link_b].name);
  return name;
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
  s.confirm_meshes = options.confirm_meshes;
  BuildAdjacency(robot, &s);
  for (const auto& [na, nb] : options.disabled_pairs) {
    s.disabled.insert(internal::PairKey(FindLink(robot, na), FindLink(robot, nb)));
  }
  AddRobotShapes(robot, options, &s);
  internal::BuildSkipTable(&s);
  AddEnvironmentShapes(env, options, &s);
  // Broadphase managers, built in one pass (a top-down median split, O(n log n)) on the robot
  // posed at its reference configuration (zero, moved into the limits): boxes inserted one by
  // one, all at the origin, would make a degenerate tree (O(n²) set-up, slow traversals).
  {
    KinematicsData kin(robot);
    const Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot))
                                  .cwiseMax(LowerLimits(robot))
                                  .cwiseMin(UpperLimits(robot));
    ForwardKinematics(robot, q, &kin);
    for (FclShape& shape : s.robot) {
      internal::Place(&shape, kin.world_from_link[shape.link] * shape.link_from_shape);
    }
  }
  std::vector<fcl::CollisionObjectd*> objects;
  objects.reserve(std::max(s.robot.size(), s.env.size()));
  for (FclShape& shape : s.robot) objects.push_back(shape.obj.get());
  s.robot_manager.registerObjects(objects);
  objects.clear();
  for (FclShape& shape : s.env) objects.push_back(shape.obj.get());
  s.env_manager.registerObjects(objects);
  s.robot_manager.setup();
  s.env_manager.setup();
}

CollisionData::~CollisionData() = default;
CollisionData::CollisionData(CollisionData&&) noexcept = default;
CollisionData& CollisionData::operator=(CollisionData&&) noexcept = default;

}  // namespace planning
