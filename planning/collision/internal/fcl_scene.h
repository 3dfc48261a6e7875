// Private: the FCL side of CollisionData. Only planning/collision/ (collision.cc building it, the
// query files querying it) includes this file.
#pragma once

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/narrowphase/collision_object.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <unordered_set>
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
  // The exact triangle mesh (OBBRSS BVH) of a robot link mesh collided as its convex hull: a hull
  // hit is confirmed on it before it counts (CollisionOptions::confirm_meshes); null otherwise.
  std::unique_ptr<fcl::CollisionObjectd> exact;
  // Set by Place with every pose of `obj` (the queries read these instead of asking FCL): the
  // shape's local z axis in the world, and its bounding capsule's core segment, start and span
  // (zero for a shape without bound_radius).
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d bound_start = Eigen::Vector3d::Zero();
  Eigen::Vector3d bound_span = Eigen::Vector3d::Zero();
};

// Poses `shape` at world_from_shape: its FCL object's transform and world AABB, and the cached
// axis and bounding segment (the same arithmetic as on the FCL object's pose, so the same bits).
inline void Place(FclShape* shape, const Eigen::Isometry3d& world_from_shape) {
  shape->obj->setTransform(world_from_shape);
  shape->obj->computeAABB();
  shape->axis = shape->obj->getRotation().col(2);
  shape->bound_start = shape->obj->getTranslation() - shape->bound_half_length * shape->axis;
  shape->bound_span = 2.0 * shape->bound_half_length * shape->axis;
}

struct FclScene {
  std::vector<FclShape> robot;  // pointers to elements are used as FCL user data: never resized
  std::vector<FclShape> env;
  // Which self pairs are never checked, in O(1) per pair without an n × n table (set-up is
  // O(n log n) in links): per link its rigid body (the link its fixed joints hang from), per body
  // the nearest ancestor body with collision geometry (−1 if none); a pair of the same body or of a
  // body and that parent is adjacent. `disabled` holds the disabled link pairs (SRDF, options) as
  // PairKey(min, max).
  std::vector<int> body;
  std::vector<int> parent_body;
  std::unordered_set<std::uint64_t> disabled;
  // skip_self[i · robot.size() + j]: robot shapes i and j are never checked (self collision off,
  // adjacent or disabled links), the same answer as the rule above in one load; built by
  // BuildSkipTable, empty (the rule above is used) for more than kMaxSkipTableShapes shapes.
  std::vector<std::uint8_t> skip_self;
  static constexpr size_t kMaxSkipTableShapes = 512;
  bool self_collision = true;
  bool environment = true;
  bool confirm_meshes = true;  // CollisionOptions::confirm_meshes
  fcl::DynamicAABBTreeCollisionManagerd robot_manager;
  fcl::DynamicAABBTreeCollisionManagerd env_manager;
};

// Fills scene->skip_self from the robot shapes, body, parent_body, disabled and self_collision
// (call once they are set).
void BuildSkipTable(FclScene* scene);

// The key of an unordered link pair.
inline std::uint64_t PairKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

}  // namespace planning::internal
