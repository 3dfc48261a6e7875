// Private: the FCL side of CollisionData. Only planning/collision/collision.cc (building it) and
// collision_queries.cc (querying it) include this file.
#pragma once

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/narrowphase/collision_object.h>

#include <Eigen/Geometry>
#include <memory>
#include <utility>
#include <vector>

namespace planning::internal {

// One collision shape: a robot link's geometry (object == −1) or an environment object's.
struct FclShape {
  int link = -1;    // robot link, or the object's link
  int object = -1;  // −1 for robot shapes, else index into Environment::objects
  int index = 0;    // position in FclScene::robot / env
  Eigen::Isometry3d link_from_shape = Eigen::Isometry3d::Identity();
  std::unique_ptr<fcl::CollisionObjectd> obj;
  // Capsules answered in closed form (CollisionOptions::analytic_capsules): radius and half the
  // length of the core segment along the shape's local z; radius 0 = not a capsule / use FCL.
  double capsule_radius = 0.0;
  double capsule_half_length = 0.0;
  // A capsule along the shape's local z that contains it (spheres, cylinders, capsules; radius 0
  // for other shapes): a lower bound on pair distances that spares the narrow phase of pairs whose
  // bounding capsules are already `margin` apart.
  double bound_radius = 0.0;
  double bound_half_length = 0.0;
};

// A candidate pair for distance queries: shape indices (b into env if env_pair) and the AABB test
// is done per query.
struct FclPair {
  int a = 0;
  int b = 0;
  bool env_pair = false;
};

struct FclScene {
  std::vector<FclShape> robot;  // pointers to elements are used as FCL user data: never resized
  std::vector<FclShape> env;
  // Self pairs that are never checked, over the links that have collision shapes only (a robot
  // with many geometry-free frames stays small): geo_row[link] is the link's row (−1 without
  // shapes); skip is num_links × num_links over those rows.
  std::vector<int> geo_row;
  std::vector<char> skip;
  int num_links = 0;
  bool self_collision = true;
  bool environment = true;
  std::vector<FclPair> pairs;  // every checked shape pair, ordered (self first, then by object)
  std::vector<std::pair<double, int>> order;  // MinDistance scratch: (AABB gap, pair index)
  fcl::DynamicAABBTreeCollisionManagerd robot_manager;
  fcl::DynamicAABBTreeCollisionManagerd env_manager;
};

}  // namespace planning::internal
