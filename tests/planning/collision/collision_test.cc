// FCL collision and distance: known free / colliding configurations, witness points and normals,
// the distance gradient, and the narrow-phase counter.
#include "planning/collision/collision.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "planning/robot/robot_io.h"
#include "tests/planning/robot/robot_test_util.h"

namespace planning {
namespace {

// A sphere (r 0.1) on a prismatic x joint; the obstacle is a sphere r 0.1 at (1, 0, 0).
const char* kSlider = R"(<robot name="slider">
  <link name="base"/>
  <joint name="x" type="prismatic"><parent link="base"/><child link="ball"/>
    <axis xyz="1 0 0"/><limit lower="-2" upper="2" velocity="1" effort="1"/></joint>
  <link name="ball"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
</robot>)";

Environment SphereAt(const Eigen::Vector3d& p) {
  Geometry g;
  g.kind = Geometry::Kind::kSphere;
  g.size = Eigen::Vector3d(0.1, 0, 0);
  Environment env;
  AddObject(MakePrimitiveObject("obstacle", g), Eigen::Isometry3d(Eigen::Translation3d(p)),
            "obstacle", &env);
  return env;
}

TEST(Collision, SpheresFreeAndColliding) {
  const Robot robot = ParseRobot(kSlider, "slider", "");
  const Environment env = SphereAt(Eigen::Vector3d(1, 0, 0));
  KinematicsData kin(robot);
  CollisionData coll(robot, env);
  Eigen::VectorXd q(1);
  q << 0.0;
  ForwardKinematics(robot, q, &kin);
  EXPECT_FALSE(InCollision(robot, kin, &coll));
  ProximityPair closest;
  EXPECT_NEAR(MinDistance(robot, kin, &coll, &closest), 0.8, 1e-6);
  EXPECT_EQ(closest.link_a, FindLink(robot, "ball"));
  EXPECT_EQ(closest.link_b, -1);
  EXPECT_EQ(closest.object, 0);
  EXPECT_TRUE(closest.point_a.isApprox(Eigen::Vector3d(0.1, 0, 0), 1e-6));
  EXPECT_TRUE(closest.point_b.isApprox(Eigen::Vector3d(0.9, 0, 0), 1e-6));
  EXPECT_TRUE(closest.normal.isApprox(Eigen::Vector3d(-1, 0, 0), 1e-6));

  q << 0.85;  // 5 cm penetration
  ForwardKinematics(robot, q, &kin);
  ProximityPair hit;
  EXPECT_TRUE(InCollision(robot, kin, &coll, &hit));
  EXPECT_EQ(hit.object, 0);
  EXPECT_NEAR(MinDistance(robot, kin, &coll, &closest), -0.05, 1e-4);
  EXPECT_GT(closest.normal.dot(Eigen::Vector3d(-1, 0, 0)), 0.99);
}

TEST(Collision, CounterCountsQueriesAndNarrowPhaseCalls) {
  const Robot robot = ParseRobot(kSlider, "slider", "");
  // Obstacle off the slider's line: at q = 1 the bounding boxes overlap but the spheres are
  // √2·0.15 − 0.2 ≈ 0.0121 m apart.
  const Environment env = SphereAt(Eigen::Vector3d(1, 0.15, 0.15));
  KinematicsData kin(robot);
  CollisionData coll(robot, env);
  Eigen::VectorXd q(1);
  q << 0.0;
  ForwardKinematics(robot, q, &kin);
  for (int i = 0; i < 5; ++i) InCollision(robot, kin, &coll);
  EXPECT_EQ(coll.queries, 5);
  EXPECT_EQ(coll.narrow_phase_calls, 0);  // boxes far apart: the broadphase prunes the pair
  q << 1.0;
  ForwardKinematics(robot, q, &kin);
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(InCollision(robot, kin, &coll));
  EXPECT_EQ(coll.queries, 8);
  // The spheres' bounding capsules (the spheres themselves) are 0.0121 m apart: no contact is
  // possible, so the boolean check never reaches the narrow phase.
  EXPECT_EQ(coll.narrow_phase_calls, 0);
  std::vector<ProximityPair> pairs;
  ComputeProximity(robot, kin, 0.1, &coll, &pairs);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_NEAR(pairs[0].distance, std::sqrt(2.0) * 0.15 - 0.2, 1e-6);
  EXPECT_EQ(coll.narrow_phase_calls, 1);
  // Margin 0.01 < the bound gap: pruned before the narrow phase.
  ComputeProximity(robot, kin, 0.01, &coll, &pairs);
  EXPECT_TRUE(pairs.empty());
  EXPECT_EQ(coll.narrow_phase_calls, 1);
  EXPECT_EQ(coll.queries, 10);
  // Overlapping spheres reach the narrow phase.
  q << 1.0;
  const Environment touching = SphereAt(Eigen::Vector3d(1, 0.1, 0.1));
  CollisionData coll2(robot, touching);
  EXPECT_TRUE(InCollision(robot, kin, &coll2));
  EXPECT_EQ(coll2.narrow_phase_calls, 1);
}

// A few LWR4 + SDH configurations with known answers.
class LwrCollision : public ::testing::Test {
 protected:
  LwrCollision() : robot(LoadRobot(AssetFile("robots/lwr4_sdh.urdf"))), kin(robot) {
    Geometry box;
    box.kind = Geometry::Kind::kBox;
    box.size = Eigen::Vector3d(0.2, 0.2, 0.2);
    AddObject(MakePrimitiveObject("block", box),
              Eigen::Isometry3d(Eigen::Translation3d(0.7, 0, 0.3)), "block", &env);
  }
  bool Check(const Eigen::VectorXd& q, ProximityPair* hit = nullptr) {
    ForwardKinematics(robot, q, &kin);
    return InCollision(robot, kin, coll.get(), hit);
  }
  void SetUp() override { coll = std::make_unique<CollisionData>(robot, env); }
  Robot robot;
  KinematicsData kin;
  Environment env;
  std::unique_ptr<CollisionData> coll;
};

TEST_F(LwrCollision, ZeroIsFree) {
  ProximityPair hit;
  EXPECT_FALSE(Check(Eigen::VectorXd::Zero(14), &hit))
      << robot.links[hit.link_a].name << " vs "
      << (hit.link_b >= 0 ? robot.links[hit.link_b].name : "block");
  EXPECT_GT(MinDistance(robot, kin, coll.get()), 0.0);
}

TEST_F(LwrCollision, ArmHitsTheBlockWhenHorizontal) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(14);
  q[1] = -M_PI / 2;  // J2 about −y: the arm points along +x at shoulder height 0.3105
  ProximityPair hit;
  EXPECT_TRUE(Check(q, &hit));
  EXPECT_EQ(hit.object, 0);
  q[0] = M_PI / 2;  // turn away about J1: free
  EXPECT_FALSE(Check(q));
}

TEST_F(LwrCollision, CrossedFingersSelfCollide) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(14);
  q[7] = M_PI / 2;  // fingers 1 and 2 face each other
  EXPECT_FALSE(Check(q));
  q[8] = 0.6;   // finger 1 proximal
  q[10] = 0.6;  // finger 2 proximal
  ProximityPair hit;
  ASSERT_TRUE(Check(q, &hit));
  EXPECT_EQ(hit.object, -1);
  const std::string a = robot.links[hit.link_a].name, b = robot.links[hit.link_b].name;
  EXPECT_TRUE(a.find("finger_1") != std::string::npos || b.find("finger_1") != std::string::npos)
      << a << " / " << b;
  // Self-collision off: free again (the block is far from the hand).
  CollisionOptions options;
  options.self_collision = false;
  CollisionData no_self(robot, env, options);
  EXPECT_FALSE(InCollision(robot, kin, &no_self));
}

// Gradient of the signed distance on smooth shapes: the 20-capsule arm against itself, a sphere
// and the pole (capsules and spheres have C¹ distances and accurate FCL witness points).
TEST(Collision, DistanceGradientMatchesFiniteDifferences) {
  const Robot robot = LoadRobot(AssetFile("robots/arm20_sdh.urdf"));
  KinematicsData kin(robot);
  Environment env;
  Geometry ball;
  ball.kind = Geometry::Kind::kSphere;
  ball.size = Eigen::Vector3d(0.15, 0, 0);
  AddObject(MakePrimitiveObject("ball", ball),
            Eigen::Isometry3d(Eigen::Translation3d(0.6, -0.6, 1.6)), "ball", &env);
  AddObject(LoadRobot(AssetFile("objects/pole.urdf")),
            Eigen::Isometry3d(Eigen::Translation3d(0.5, 0.2, 1.5)), "pole", &env);
  auto coll = std::make_unique<CollisionData>(robot, env);
  std::mt19937 rng(3);
  const int n = num_dofs(robot);
  Eigen::MatrixXd Ja(3, n), Jb(3, n);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<ProximityPair> pairs, pairs_h;
  // Distance of the pair (link_a, link_b, object) at q.
  auto pair_distance = [&](const Eigen::VectorXd& q, const ProximityPair& key) {
    ForwardKinematics(robot, q, &kin);
    ComputeProximity(robot, kin, inf, coll.get(), &pairs_h);
    for (const ProximityPair& p : pairs_h) {
      if (p.link_a == key.link_a && p.link_b == key.link_b && p.object == key.object) {
        return p.distance;
      }
    }
    return inf;
  };
  int checked = 0;
  for (int trial = 0; trial < 4; ++trial) {
    Eigen::VectorXd q = 0.4 * RandomQ(robot, &rng);
    q.tail(7).setZero();  // the SDH is not part of this check
    ForwardKinematics(robot, q, &kin);
    ComputeProximity(robot, kin, 0.5, coll.get(), &pairs);
    const std::vector<ProximityPair> at_q = pairs;
    int visited[3] = {0, 0, 0};  // per kind: self, ball, pole
    for (const ProximityPair& p : at_q) {
      // Pairs that move relative to each other and are clearly apart (smooth distance).
      const bool arm_a = robot.links[p.link_a].name.rfind("arm_link", 0) == 0;
      const bool arm_b = p.link_b < 0 || robot.links[p.link_b].name.rfind("arm_link", 0) == 0;
      if (p.distance < 0.005 || !arm_a || !arm_b || ++visited[p.object + 1] > 3) continue;
      ForwardKinematics(robot, q, &kin);
      // ∂d/∂q = nᵀ (J_a(p_a) − J_b(p_b)), witness points held fixed on their links.
      PointJacobian(robot, kin, p.link_a, kin.world_from_link[p.link_a].inverse() * p.point_a, Ja);
      Eigen::RowVectorXd grad = p.normal.transpose() * Ja;
      if (p.link_b >= 0) {
        PointJacobian(robot, kin, p.link_b, kin.world_from_link[p.link_b].inverse() * p.point_b,
                      Jb);
        grad -= p.normal.transpose() * Jb;
      }
      const double h = 1e-6;
      Eigen::RowVectorXd fd(n);
      for (int k = 0; k < n; ++k) {
        Eigen::VectorXd qp = q, qm = q;
        qp[k] += h;
        qm[k] -= h;
        fd[k] = (pair_distance(qp, p) - pair_distance(qm, p)) / (2 * h);
      }
      // FCL (libccd GJK) witness points carry ~1e-4 relative error, so sphere–capsule gradients
      // (O(0.1–1)) are checked to 2e-3. Capsule–capsule witnesses are also non-unique for
      // near-parallel segments: check the direction only.
      if (p.object == 0) {
        EXPECT_LT((grad - fd).cwiseAbs().maxCoeff(), 2e-3)
            << robot.links[p.link_a].name << " vs "
            << (p.link_b >= 0 ? robot.links[p.link_b].name : "object") << "\n grad " << grad
            << "\n fd   " << fd;
        ++checked;
      } else if (fd.norm() > 0.05) {
        EXPECT_GT(grad.dot(fd) / (grad.norm() * fd.norm()), 0.99)
            << robot.links[p.link_a].name << " vs "
            << (p.link_b >= 0 ? robot.links[p.link_b].name : "pole");
      }
    }
  }
  EXPECT_GE(checked, 3);
}

// The pole (rope) along world y at x = −0.1, z = 1.85, centred at y = `y`.
Environment RopeAlongY(double y) {
  Environment env;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(-0.1, y, 1.85));
  pose.rotate(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  AddObject(LoadRobot(AssetFile("objects/pole.urdf")), pose, "rope", &env);
  return env;
}

TEST(Collision, Arm20CoilIsFreeAroundTheRope) {
  const Robot robot = LoadRobot(AssetFile("robots/arm20_sdh.urdf"));
  // The rope of thesis §4.3.1: along world y, x = −0.1, z = 1.85, from y = −3 to 0. Its end
  // at y = 0 would pierce the stem (r 0.1 about the z axis), so it is shifted 0.2 m along −y here.
  const Environment env = RopeAlongY(-1.7);
  KinematicsData kin(robot);
  CollisionData coll(robot, env);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  ProximityPair hit;
  const bool colliding = InCollision(robot, kin, &coll, &hit);
  EXPECT_FALSE(colliding) << robot.links[hit.link_a].name << " vs "
                          << (hit.link_b >= 0 ? robot.links[hit.link_b].name : "rope");
  // The rope's axis chain in the world: along y at x = −0.1, z = 1.85.
  const Eigen::Matrix3Xd axis = ObjectChainPoints(env, 0, 0);
  EXPECT_TRUE(axis.col(0).isApprox(Eigen::Vector3d(-0.1, -3.2, 1.85), 1e-12));
  EXPECT_TRUE(axis.col(1).isApprox(Eigen::Vector3d(-0.1, -0.2, 1.85), 1e-12));
}

// The bounding-capsule pre-check (cylinders and capsules of the arm, the SDH and the pole) only
// spares narrow-phase calls: on random poses the boolean check agrees with the sign of the exact
// minimum distance (found without the pre-check) and ComputeProximity's closest pair equals it
// whenever it is inside the margin (and MinDistance reports the deepest penetration: it stopped at
// the first overlapping pair before).
TEST(Collision, BoundPreCheckChangesNoAnswer) {
  const Robot robot = LoadRobot(AssetFile("robots/arm20_sdh.urdf"));
  const Environment env = RopeAlongY(-1.65);  // where unwrap.json places it
  KinematicsData kin(robot);
  CollisionData coll(robot, env), coll_min(robot, env);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  const double margin = 0.15;
  int colliding = 0, close = 0;
  long pruned = 0;
  std::vector<ProximityPair> pairs;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd q(num_dofs(robot));
    for (Eigen::Index k = 0; k < q.size(); ++k) q[k] = u(rng);
    ForwardKinematics(robot, q, &kin);
    const double d = MinDistance(robot, kin, &coll_min);
    if (std::abs(d) < 1e-6) continue;  // touching: either answer is within FCL's tolerance
    const long before = coll.narrow_phase_calls;
    EXPECT_EQ(InCollision(robot, kin, &coll), d < 0.0) << "trial " << trial << ", d " << d;
    ComputeProximity(robot, kin, margin, &coll, &pairs);
    pruned += coll.narrow_phase_calls - before;
    double closest = std::numeric_limits<double>::infinity();
    for (const ProximityPair& p : pairs) closest = std::min(closest, p.distance);
    if (d < margin) {
      EXPECT_NEAR(closest, d, 1e-9) << "trial " << trial;
      ++close;
    } else {
      EXPECT_TRUE(pairs.empty()) << "trial " << trial;
    }
    colliding += d < 0.0;
  }
  EXPECT_GT(colliding, 10);
  EXPECT_GT(close, 50);
  EXPECT_GT(pruned, 0);
}

TEST(Collision, HumanHandRestPoseIsFree) {
  const Robot robot = LoadRobot(AssetFile("robots/human_hand.urdf"));
  KinematicsData kin(robot);
  CollisionData coll(robot, Environment{});
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  ProximityPair hit;
  EXPECT_FALSE(InCollision(robot, kin, &coll, &hit))
      << robot.links[hit.link_a].name << " vs " << robot.links[hit.link_b].name;
}

TEST(Collision, MeshObjectsCollide) {
  const Robot robot = ParseRobot(kSlider, "slider", "");
  Environment env;
  AddObject(LoadRobot(AssetFile("objects/mug.urdf")),
            Eigen::Isometry3d(Eigen::Translation3d(1.0, 0, -0.04)), "mug", &env);
  KinematicsData kin(robot);
  CollisionData coll(robot, env);
  Eigen::VectorXd q(1);
  q << 1.0;  // the ball sits inside the open cup: touches nothing (cup radius 0.035 < 0.1? no)
  ForwardKinematics(robot, q, &kin);
  EXPECT_TRUE(InCollision(robot, kin, &coll));  // ball r 0.1 is wider than the cup: hits the rim
  q << 0.5;
  ForwardKinematics(robot, q, &kin);
  EXPECT_FALSE(InCollision(robot, kin, &coll));
  EXPECT_NEAR(MinDistance(robot, kin, &coll), 0.5 - 0.1 - 0.04, 2e-3);
}

}  // namespace
}  // namespace planning
