// Convex hulls are the first test, the exact meshes the verdict: a hull hit where the triangles do
// not meet is "hull-only" (not a collision); a 1 mm interpenetration is a collision. Also checks
// that the broadphase set-up scales: a 10,000-link chain is built and checked.
#include <gtest/gtest.h>

#include <string>

#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace planning {
namespace {

// Appends the 12 triangles (outward, counter-clockwise) of the box [lo, hi] to `mesh`.
void AddBox(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, Mesh* mesh) {
  const int b = static_cast<int>(mesh->vertices.size());
  for (int i = 0; i < 8; ++i) {
    mesh->vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                                i & 4 ? hi.z() : lo.z());
    mesh->normals.emplace_back(0.f, 0.f, 1.f);
  }
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) mesh->triangles.emplace_back(b + f[0], b + f[1], b + f[2]);
}

// A "U" in the xy plane: two arms x ∈ ±[0.08, 0.10], y ∈ [−0.08, 0.10], joined by a bottom bar
// y ∈ [−0.10, −0.08]; z ∈ [−0.05, 0.05]. Its convex hull is the box [−0.1, 0.1]² × [−0.05, 0.05],
// which contains the gap |x| < 0.08 the mesh leaves open.
Mesh UMesh() {
  Mesh m;
  AddBox({-0.10f, -0.08f, -0.05f}, {-0.08f, 0.10f, 0.05f}, &m);
  AddBox({0.08f, -0.08f, -0.05f}, {0.10f, 0.10f, 0.05f}, &m);
  AddBox({-0.10f, -0.10f, -0.05f}, {0.10f, -0.08f, 0.05f}, &m);
  return m;
}

// A peg: the box x ∈ [−0.03, 0.03], y ∈ [0, 0.06], z ∈ [−0.03, 0.03], as a mesh.
Mesh PegMesh() {
  Mesh m;
  AddBox({-0.03f, 0.0f, -0.03f}, {0.03f, 0.06f, 0.03f}, &m);
  return m;
}

Geometry MeshGeometry(int index) {
  Geometry g;
  g.kind = Geometry::Kind::kMesh;
  g.mesh = index;
  g.size = Eigen::Vector3d::Ones();
  return g;
}

// base ─(prismatic z, ±1 mm)→ u (U mesh); base ─(prismatic x)→ peg (peg mesh). u and peg are
// siblings, not adjacent, so their self-collision is checked. q = (u_lift, peg_x).
Robot UAndPeg() {
  Robot r;
  r.name = "u_and_peg";
  r.source = "<test>";
  r.meshes = {UMesh(), PegMesh()};
  r.links.resize(3);
  r.links[0].name = "base";
  r.links[1].name = "u";
  r.links[1].collisions.push_back(MeshGeometry(0));
  r.links[2].name = "peg";
  r.links[2].collisions.push_back(MeshGeometry(1));
  const char* names[2] = {"u_lift", "peg_x"};
  const Eigen::Vector3d axes[2] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX()};
  for (int k = 0; k < 2; ++k) {
    Joint j;
    j.name = names[k];
    j.type = JointType::kPrismatic;
    j.parent_link = 0;
    j.child_link = k + 1;
    j.axis = axes[k];
    j.limits.lower = -0.2;
    j.limits.upper = 0.2;
    j.dof = k;
    r.joints.push_back(j);
    r.links[k + 1].parent_joint = k;
    r.dof_joints.push_back(k);
  }
  return r;
}

CollisionReport Check(const Robot& robot, const Environment& env, const CollisionOptions& options,
                      double u_lift, double peg_x) {
  KinematicsData kin(robot);
  CollisionData coll(robot, env, options);
  ForwardKinematics(robot, Eigen::Vector2d(u_lift, peg_x), &kin);
  const CollisionReport report = CheckCollisions(robot, kin, &coll);
  EXPECT_EQ(InCollision(robot, kin, &coll), report.in_collision) << "peg_x " << peg_x;
  return report;
}

TEST(ExactConfirm, HullOverlapOfAConcaveMeshIsNotACollision) {
  const Robot robot = UAndPeg();
  // Peg in the middle of the gap, and 1 mm short of the right arm (x = 0.049 + 0.03 = 0.079).
  for (double x : {0.0, 0.049, -0.049}) {
    const CollisionReport r = Check(robot, {}, {}, 0.0, x);
    EXPECT_FALSE(r.in_collision) << x;
    EXPECT_TRUE(r.pairs.empty()) << x;
    ASSERT_EQ(r.hull_only.size(), 1u) << x;  // the hulls do overlap
    EXPECT_EQ(r.hull_only[0].link_a, 1);
    EXPECT_EQ(r.hull_only[0].link_b, 2);
  }
  // Without the confirmation the hull decides: in collision.
  CollisionOptions hulls_only;
  hulls_only.confirm_meshes = false;
  EXPECT_TRUE(Check(robot, {}, hulls_only, 0.0, 0.0).in_collision);
  // Exact meshes from the start agree with hull + confirmation.
  CollisionOptions exact;
  exact.exact_meshes = true;
  EXPECT_FALSE(Check(robot, {}, exact, 0.0, 0.0).in_collision);
}

TEST(ExactConfirm, OneMillimetreInterpenetrationIsACollision) {
  const Robot robot = UAndPeg();
  // x = 0.051: the peg's face at 0.081 is 1 mm inside the right arm (which starts at 0.08).
  for (double x : {0.051, -0.051}) {
    for (double lift : {0.0, 0.001, -0.001}) {
      const CollisionReport r = Check(robot, {}, {}, lift, x);
      EXPECT_TRUE(r.in_collision) << x << " " << lift;
      ASSERT_EQ(r.pairs.size(), 1u);
      EXPECT_EQ(r.pairs[0].link_a, 1);
      EXPECT_EQ(r.pairs[0].link_b, 2);
      EXPECT_TRUE(r.hull_only.empty());
      CollisionOptions exact;
      exact.exact_meshes = true;
      EXPECT_TRUE(Check(robot, {}, exact, lift, x).in_collision);
    }
  }
}

TEST(ExactConfirm, RobotHullAgainstAnEnvironmentPrimitive) {
  // Only the U on the robot (the peg link has no geometry); a box obstacle in the gap.
  Robot robot = UAndPeg();
  robot.links[2].collisions.clear();
  Geometry box;
  box.kind = Geometry::Kind::kBox;
  box.size = Eigen::Vector3d(0.06, 0.06, 0.06);
  for (const auto& [x, hit] : {std::pair{0.0, false}, {0.049, false}, {0.051, true}}) {
    Environment env;
    AddObject(MakePrimitiveObject("box", box),
              Eigen::Isometry3d(Eigen::Translation3d(x, 0.03, 0.0)), "box", &env);
    const CollisionReport r = Check(robot, env, {}, 0.0, 0.0);
    EXPECT_EQ(r.in_collision, hit) << x;
    EXPECT_EQ(r.hull_only.size(), hit ? 0u : 1u) << x;
    if (hit) {
      ASSERT_EQ(r.pairs.size(), 1u);
      EXPECT_EQ(r.pairs[0].object, 0);
      EXPECT_EQ(r.pairs[0].link_b, -1);
    }
  }
}

// A chain of n capsule links, 0.1 m apart along z at q = 0 (straight, free); with every joint at
// its limit (1 rad alternately about x and y) it folds onto itself.
std::string CapsuleChain(int n) {
  std::string urdf = "<robot name=\"chain\">\n";
  for (int i = 0; i < n; ++i) {
    urdf += "<link name=\"l" + std::to_string(i) +
            "\"><collision name=\"capsule\"><origin xyz=\"0 0 0.05\"/><geometry><cylinder "
            "radius=\"0.02\" length=\"0.06\"/></geometry></collision></link>\n";
  }
  for (int i = 1; i < n; ++i) {
    urdf += "<joint name=\"j" + std::to_string(i) + "\" type=\"revolute\"><parent link=\"l" +
            std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) +
            "\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"" + (i % 2 ? "1 0 0" : "0 1 0") +
            "\"/><limit lower=\"-3\" upper=\"3\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  return urdf + "</robot>\n";
}

TEST(CollisionScale, TenThousandLinkChainSetsUpAndChecks) {
  const Robot robot = ParseRobot(CapsuleChain(10000), "chain.urdf", "");
  ASSERT_EQ(robot.links.size(), 10000u);
  KinematicsData kin(robot);
  CollisionData coll(robot, {});
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  CollisionReport r = CheckCollisions(robot, kin, &coll);
  EXPECT_FALSE(r.in_collision);
  EXPECT_EQ(coll.narrow_phase_calls, 0);  // only adjacent capsules touch, and they are skipped
  // Fold it: every joint at 3 rad turns the chain back onto itself.
  ForwardKinematics(robot, Eigen::VectorXd::Constant(num_dofs(robot), 3.0), &kin);
  r = CheckCollisions(robot, kin, &coll, 10);
  EXPECT_TRUE(r.in_collision);
  EXPECT_EQ(r.pairs.size(), 10u);
}

}  // namespace
}  // namespace planning
