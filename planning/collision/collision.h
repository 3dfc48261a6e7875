// Collision checking and distance queries with FCL: robot against a static environment, and
// robot self-collision (adjacent links skipped, see AreAdjacent in robot.h).
//
//   Environment env;                                    // static objects, world frame
//   AddObject(LoadRobot("assets/objects/pole.urdf"), world_from_pole, "pole", &env);
//   CollisionData coll(robot, env);                     // FCL objects + broadphase, sized once
//   ForwardKinematics(robot, q, &kin);
//   bool hit = InCollision(robot, kin, &coll);          // boolean validity check
//   ComputeProximity(robot, kin, 0.05, &coll, &pairs);  // pairs closer than 5 cm, with witnesses
//   coll.narrow_phase_calls                             // the counter planners/benchmarks read
//
// Shapes: box, sphere, cylinder and capsule map to FCL primitives. Robot link meshes become FCL
// convex shapes of their convex hulls (qhull; planning/robot/mesh_io.h ConvexHull) unless
// CollisionOptions::exact_meshes is set; environment meshes (rings, mugs: not convex) and flat
// meshes without a solid hull use an OBBRSS BVH of their triangles (distances of penetrating
// meshes come from the contact's penetration depth). Distance queries between two capsules (the
// arms' links and the poles) can be computed in closed form (segment–segment closest points minus
// the radii, see CollisionOptions::analytic_capsules). Boolean checks run through
// dynamic AABB trees (broadphase) and stop at the first colliding pair; distance queries skip
// pairs whose bounding boxes are farther apart than the margin. FCL types never appear in this
// header.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"

namespace planning {

namespace internal {
struct FclScene;  // FCL objects and broadphase managers (planning/collision/internal/fcl_scene.h)
}

// A static object placed in the world: any Robot (usually a single-link object URDF from
// assets/objects/), evaluated at its zero configuration and moved by world_from_object.
struct PlacedObject {
  std::string name;
  Robot model;
  Eigen::Isometry3d world_from_object = Eigen::Isometry3d::Identity();
};

// The static environment: placed objects. Immutable while a CollisionData built from it lives.
struct Environment {
  std::vector<PlacedObject> objects;
};

// Appends `object` at `world_from_object`. Throws std::invalid_argument if the name is taken.
void AddObject(const Robot& object, const Eigen::Isometry3d& world_from_object,
               const std::string& name, Environment* env);

// A one-link object made of a single primitive (box/sphere/cylinder/capsule), used as both its
// visual and collision geometry, e.g. for obstacles declared inline in a scenario. Throws
// std::invalid_argument for a size that is not finite or negative, or a radius <= 0.
Robot MakePrimitiveObject(const std::string& name, const Geometry& geometry);

// World positions of chain `chain` of object `object` (3 × ChainSize, closed chains repeat their
// first point, as in ChainPoints).
Eigen::Matrix3Xd ObjectChainPoints(const Environment& env, int object, int chain);

// Index of the object with this name; throws std::invalid_argument if there is none.
int FindObject(const Environment& env, const std::string& name);

struct CollisionOptions {
  bool self_collision = true;  // check robot links against each other (non-adjacent pairs)
  bool environment = true;     // check robot links against the environment
  // Further link pairs (by name) never checked against each other, e.g. links that touch by
  // design. Unknown names throw std::invalid_argument at construction.
  std::vector<std::pair<std::string, std::string>> disabled_pairs;
  // Robot link meshes: false (default) collide as their convex hulls (fast, conservative: a hull
  // contains the mesh); true as exact triangle BVHs (slow on real robot meshes).
  bool exact_meshes = false;
  // With hulls (exact_meshes false): a hull hit of a link mesh is confirmed on the mesh's exact
  // triangles (an OBBRSS BVH) before it counts as a collision, so the concave parts of a mesh
  // (the inside of a gripper) do not collide; the hull stays the fast first test. Distances stay
  // those of the hulls (smooth gradients). CheckCollisions reports hull-only hits separately.
  bool confirm_meshes = true;
  // Capsule–capsule distance queries: true in closed form (segment–segment distance minus the
  // radii, exact also when penetrating, where FCL's EPA depth can be several cm too deep; one
  // narrow-phase call, ≈ 20× cheaper), false (default, so results of existing set-ups do not
  // change; the scenario key collision.analytic_capsules sets it, unwrap.json does) through FCL's
  // GJK/EPA. Boolean checks (InCollision) always use FCL.
  bool analytic_capsules = false;
};

// Mutable collision workspace for one robot + environment: one FCL object per collision shape,
// a dynamic AABB tree of the robot's shapes (refreshed on every query from the kinematics) and a
// static one of the environment. Not copyable; one per thread.
struct CollisionData {
  CollisionData(const Robot& robot, const Environment& env, const CollisionOptions& options = {});
  ~CollisionData();
  CollisionData(CollisionData&&) noexcept;
  CollisionData& operator=(CollisionData&&) noexcept;
  CollisionData(const CollisionData&) = delete;
  CollisionData& operator=(const CollisionData&) = delete;

  // THE counter of narrow-phase calls: incremented once per FCL collide() or distance() call (or
  // closed-form capsule distance) on a shape pair that survived the broadphase, the adjacency
  // filter and, for spheres, cylinders and capsules, the bounding-capsule test. Planners and
  // benchmarks read it (and may reset it to 0).
  std::int64_t narrow_phase_calls = 0;
  // Configuration-level queries: one per InCollision / ComputeProximity / MinDistance call.
  std::int64_t queries = 0;
  // narrow_phase_calls split by kind (their sum): yes/no FCL collide() calls of InCollision and
  // CheckCollisions (mesh confirmations included), and distance evaluations (FCL distance(), the
  // closed-form capsule distance, the contact collide() of a penetrating pair) of ComputeProximity
  // and MinDistance.
  std::int64_t bool_pair_tests = 0;
  std::int64_t distance_pair_tests = 0;

  std::unique_ptr<internal::FclScene> scene;
};

// The cost units every planner is measured in (one set of counters, filled the same way by AICO,
// the RRTs and the OMPL peers; docs/results/unwrap.md):
//   state_queries        validity or clearance evaluations of one configuration (a boolean
//                        InCollision, a ComputeProximity, a line-clearance or winding evaluation);
//   bool_pair_tests      yes/no narrow-phase pair tests (stop at the first hit);
//   distance_pair_tests  distance evaluations of one pair (FCL distance or penetration, closed-form
//                        capsule distance, segment-to-line distance).
struct QueryCounts {
  std::int64_t state_queries = 0;
  std::int64_t bool_pair_tests = 0;
  std::int64_t distance_pair_tests = 0;
  std::int64_t pair_tests() const { return bool_pair_tests + distance_pair_tests; }
  QueryCounts& operator+=(const QueryCounts& o) {
    state_queries += o.state_queries;
    bool_pair_tests += o.bool_pair_tests;
    distance_pair_tests += o.distance_pair_tests;
    return *this;
  }
  friend QueryCounts operator+(QueryCounts a, const QueryCounts& b) { return a += b; }
  friend QueryCounts operator-(QueryCounts a, const QueryCounts& b) {
    a.state_queries -= b.state_queries;
    a.bool_pair_tests -= b.bool_pair_tests;
    a.distance_pair_tests -= b.distance_pair_tests;
    return a;
  }
  friend bool operator==(const QueryCounts& a, const QueryCounts& b) {
    return a.state_queries == b.state_queries && a.bool_pair_tests == b.bool_pair_tests &&
           a.distance_pair_tests == b.distance_pair_tests;
  }
};

// The counters of `coll` in these units: state_queries = queries.
inline QueryCounts Counts(const CollisionData& coll) {
  return {coll.queries, coll.bool_pair_tests, coll.distance_pair_tests};
}

// A colliding or near pair. Self pairs have object == −1 and link_b ≥ 0; environment pairs have
// link_b == −1 and object = index into Environment::objects.
struct ProximityPair {
  int link_a = -1;
  int link_b = -1;
  int object = -1;
  // Signed distance [m]: > 0 separation, < 0 penetration depth (then the witness points coincide
  // at the contact point).
  double distance = 0.0;
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();  // world frame, on link_a's surface
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();  // world frame, on link_b / the object
  // Unit normal (world) pointing from b to a: moving point_a along +normal increases the distance,
  // so ∂distance/∂q ≈ normalᵀ (J_a(point_a) − J_b(point_b)) with J_b = 0 for the environment.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

// "LINK_A vs LINK_B" for a self pair, "LINK_A vs object 'NAME'" for an environment pair; "" for
// an unset pair (link_a < 0). For messages and reports.
std::string PairName(const Robot& robot, const Environment& env, const ProximityPair& pair);

// Boolean check of the configuration in `kin` (ForwardKinematics must have been called): robot vs
// environment and non-adjacent self pairs. Stops at the first colliding shape pair; if `hit` is
// not null it receives that pair (distance/points unset). Counts one query and every narrow-phase
// call. FCL solver exceptions on degenerate contacts count as a collision.
bool InCollision(const Robot& robot, const KinematicsData& kin, CollisionData* coll,
                 ProximityPair* hit = nullptr);

// The collision state of a configuration as a check reports it: every colliding pair (confirmed on
// the exact meshes where a link mesh is collided as its hull), and the pairs whose hulls overlap
// although their meshes do not ("hull-only": not a collision). Each pair once per shape pair,
// ordered by (object, link_a, link_b); distance and points unset (a yes/no answer).
struct CollisionReport {
  bool in_collision = false;
  std::vector<ProximityPair> pairs;      // colliding pairs, at most max_pairs
  std::vector<ProximityPair> hull_only;  // hull hits the exact meshes refute
};

// All colliding pairs of the configuration in `kin` (up to max_pairs), with yes/no narrow phases
// only (no penetration depth, no distance). Counts one query and every narrow-phase call.
CollisionReport CheckCollisions(const Robot& robot, const KinematicsData& kin, CollisionData* coll,
                                int max_pairs = 100);

// Every checked link pair (per link pair, the closest of their shapes) whose distance is below
// `margin` [m], with signed distance, witness points and normal. `out` is cleared and refilled
// (capacity is reused). Pairs are ordered by (object, link_a, link_b), deterministic. Counts one
// query plus the narrow-phase calls (pairs whose bounding boxes, or bounding capsules, are
// farther than margin apart are skipped without a narrow-phase call).
void ComputeProximity(const Robot& robot, const KinematicsData& kin, double margin,
                      CollisionData* coll, std::vector<ProximityPair>* out);

// Minimum signed distance over all checked pairs (+∞ if there are none); if `closest` is not null
// it receives the closest pair (the first in checked-pair order among equal distances). Pairs are
// visited by increasing bounding-box gap and the search stops when that gap exceeds the best
// distance found (or, while it is negative, exceeds 0: every overlapping pair is visited, so a
// colliding configuration reports its deepest penetration), so far-apart pairs cost no
// narrow-phase call.
double MinDistance(const Robot& robot, const KinematicsData& kin, CollisionData* coll,
                   ProximityPair* closest = nullptr);

}  // namespace planning
