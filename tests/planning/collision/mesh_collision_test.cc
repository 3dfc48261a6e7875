// Robot link meshes as convex hulls (default) against exact triangle BVHs: both agree on clearly
// separated and clearly intersecting poses; the hull of a mesh is what ConvexHull says.
#include <gtest/gtest.h>

#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/mesh_io.h"
#include "planning/robot/robot_io.h"
#include "tests/planning/robot/robot_test_util.h"

namespace planning {
namespace {

TEST(MeshCollision, HullOfABoxIsTheBox) {
  const Mesh box = LoadMesh(TestDataFile("fake_pkg/meshes/box.stl"));
  const Mesh hull = ConvexHull(box);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.triangles.size(), 12u);
  // Outward faces: every vertex lies on the inner side of every face.
  for (const Eigen::Vector3i& t : hull.triangles) {
    const Eigen::Vector3f a = hull.vertices[t[0]];
    const Eigen::Vector3f n = (hull.vertices[t[1]] - a).cross(hull.vertices[t[2]] - a);
    for (const Eigen::Vector3f& v : hull.vertices) EXPECT_LE(n.dot(v - a), 1e-6f);
  }
  Mesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_TRUE(ConvexHull(flat).triangles.empty());
}

TEST(MeshCollision, HullAndExactAgreeOnClearPoses) {
  const Robot robot = LoadRobot(TestDataFile("fake_pkg/urdf/mesh_bot.urdf"));
  const Robot ring = LoadRobot(AssetFile("objects/ring.urdf"));
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  // The robot's base box is at the origin; the ring (an exact mesh either way) is placed far
  // away, then across the box.
  for (const double x : {2.0, 0.232}) {  // 0.232: the ring's tube runs through the box
    Environment env;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(x, 0.0, 0.0);
    AddObject(ring, pose, "ring", &env);
    CollisionOptions exact;
    exact.exact_meshes = true;
    CollisionData hull_data(robot, env), exact_data(robot, env, exact);
    const bool hull_hit = InCollision(robot, kin, &hull_data);
    EXPECT_EQ(hull_hit, InCollision(robot, kin, &exact_data)) << "x = " << x;
    const double d_hull = MinDistance(robot, kin, &hull_data);
    const double d_exact = MinDistance(robot, kin, &exact_data);
    if (x > 1.0) {
      EXPECT_FALSE(hull_hit);
      EXPECT_NEAR(d_hull, d_exact, 1e-6);  // box and tetrahedron are convex: same shapes
    } else {
      EXPECT_TRUE(hull_hit);
      EXPECT_LE(d_hull, 0.0);
      EXPECT_LE(d_exact, 0.0);
    }
  }
}

}  // namespace
}  // namespace planning
