// Forward kinematics against the LWR4 DH table, Jacobians against central differences, mimic
// joints, chains, and the thesis' coil at q = 0.
#include "planning/robot/kinematics.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <random>

#include "planning/robot/robot_io.h"
#include "tests/planning/robot/robot_test_util.h"
#include "topology/winding.h"

// Counts heap allocations in this test binary (to check the per-step path allocates nothing).
// GCC flags malloc/free inside replacement operators as mismatched; they are matched here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
static std::atomic<long> g_allocations{0};
void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace planning {
namespace {

// Standard DH: T_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i).
Eigen::Isometry3d LwrDh(const Eigen::VectorXd& q) {
  const double d[7] = {0.3105, 0, 0.40, 0, 0.39, 0, 0.078};
  const double alpha[7] = {M_PI / 2, -M_PI / 2, -M_PI / 2, M_PI / 2, M_PI / 2, -M_PI / 2, 0};
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 7; ++i) {
    t = t * Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(0, 0, d[i]) *
        Eigen::AngleAxisd(alpha[i], Eigen::Vector3d::UnitX());
  }
  return t;
}

TEST(Kinematics, LwrFlangeAtZero) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  const Eigen::Isometry3d& flange = kin.world_from_link[FindLink(robot, "lwr_link_7")];
  EXPECT_TRUE(flange.translation().isApprox(Eigen::Vector3d(0, 0, 1.1785), 1e-12));
  EXPECT_TRUE(flange.linear().isIdentity(1e-12));
  // SDH tip frames of straight fingers: 0.246 m above the mounting face (Schunk SDH URDF).
  const double palm_z = kin.world_from_link[FindLink(robot, "sdh_palm")].translation().z();
  EXPECT_NEAR(palm_z, 1.1985, 1e-12);
  EXPECT_NEAR(kin.world_from_link[FindLink(robot, "sdh_thumb_tip")].translation().z() - palm_z,
              0.246, 1e-12);
}

TEST(Kinematics, LwrMatchesDhTableForRandomQ) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  KinematicsData kin(robot);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd q = RandomQ(robot, &rng);
    ForwardKinematics(robot, q, &kin);
    const Eigen::Isometry3d dh = LwrDh(q);
    const Eigen::Isometry3d& urdf = kin.world_from_link[FindLink(robot, "lwr_link_7")];
    EXPECT_LT((dh.translation() - urdf.translation()).norm(), 1e-12);
    EXPECT_LT((dh.linear() - urdf.linear()).norm(), 1e-12);
  }
}

TEST(Kinematics, MimicJointFollowsMaster) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  KinematicsData kin(robot);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot));
  q[7] = 0.7;
  ForwardKinematics(robot, q, &kin);
  const int master = FindJoint(robot, "sdh_knuckle_joint");
  const int mimic = FindJoint(robot, "sdh_finger_2_knuckle_joint");
  EXPECT_DOUBLE_EQ(kin.joint_value[master], 0.7);
  EXPECT_DOUBLE_EQ(kin.joint_value[mimic], 0.7);
  // Opposite axes: the two knuckles turn in opposite directions about the palm normal.
  const Eigen::Matrix3d r1 = kin.world_from_link[FindLink(robot, "sdh_finger_1_knuckle")].linear();
  const Eigen::Matrix3d r2 = kin.world_from_link[FindLink(robot, "sdh_finger_2_knuckle")].linear();
  EXPECT_NEAR(r1(0, 0), r2(0, 0), 1e-12);
  EXPECT_NEAR(r1(1, 0), -r2(1, 0), 1e-12);
  // At 90° the rotating fingers face each other: their closing directions (local +x) oppose.
  q[7] = M_PI / 2;
  ForwardKinematics(robot, q, &kin);
  const Eigen::Vector3d c1 =
      kin.world_from_link[FindLink(robot, "sdh_finger_1_knuckle")].linear().col(0);
  const Eigen::Vector3d c2 =
      kin.world_from_link[FindLink(robot, "sdh_finger_2_knuckle")].linear().col(0);
  EXPECT_NEAR(c1.dot(c2), -1.0, 1e-12);
}

// Central-difference checks of every Jacobian on every shipped robot.
class JacobianFd : public ::testing::TestWithParam<const char*> {};

Eigen::Vector3d RotationLog(const Eigen::Matrix3d& r) {
  const Eigen::AngleAxisd aa(r);
  return aa.angle() * aa.axis();
}

TEST_P(JacobianFd, PointFrameAndChainJacobiansMatchFiniteDifferences) {
  const Robot robot = LoadRobot(AssetFile(GetParam()));
  const int n = num_dofs(robot);
  KinematicsData kin(robot), kp(robot), km(robot);
  std::mt19937 rng(11);
  const double h = 1e-6;
  Eigen::MatrixXd J(3, n), F(6, n);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = RandomQ(robot, &rng);
    ForwardKinematics(robot, q, &kin);
    const int link = std::uniform_int_distribution<int>(0, robot.links.size() - 1)(rng);
    const Eigen::Vector3d p(0.03, -0.02, 0.05);
    PointJacobian(robot, kin, link, p, J);
    FrameJacobian(robot, kin, link, F);
    Eigen::MatrixXd J_fd(3, n), F_fd(6, n);
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      ForwardKinematics(robot, qp, &kp);
      ForwardKinematics(robot, qm, &km);
      J_fd.col(k) = (kp.world_from_link[link] * p - km.world_from_link[link] * p) / (2 * h);
      F_fd.col(k).head<3>() =
          (kp.world_from_link[link].translation() - km.world_from_link[link].translation()) /
          (2 * h);
      F_fd.col(k).tail<3>() = RotationLog(kp.world_from_link[link].linear() *
                                          km.world_from_link[link].linear().transpose()) /
                              (2 * h);
    }
    EXPECT_LT((J - J_fd).cwiseAbs().maxCoeff(), 1e-7) << robot.links[link].name;
    EXPECT_LT((F - F_fd).cwiseAbs().maxCoeff(), 1e-7) << robot.links[link].name;
    // The directional form: row += s·uᵀ ∂p/∂q, added to a strided row of a matrix.
    const Eigen::Vector3d u = Eigen::Vector3d(0.3, -0.8, 0.52).normalized();
    Eigen::MatrixXd rows = Eigen::MatrixXd::Constant(4, n, 0.25);
    AddPointJacobianAlong(robot, kin, link, kin.world_from_link[link] * p, u, -2.0, rows.row(2));
    const Eigen::RowVectorXd expected =
        Eigen::RowVectorXd::Constant(n, 0.25) - 2.0 * u.transpose() * J_fd;
    EXPECT_LT((rows.row(2) - expected).cwiseAbs().maxCoeff(), 2e-7) << robot.links[link].name;
    EXPECT_EQ(rows.row(1), Eigen::RowVectorXd::Constant(n, 0.25));
    for (int c = 0; c < static_cast<int>(robot.chains.size()); ++c) {
      const int size = ChainSize(robot, c);
      Eigen::MatrixXd dP(3 * size, n), dP_fd(3 * size, n);
      ChainJacobian(robot, kin, c, dP);
      Eigen::Matrix3Xd pp, pm;
      for (int k = 0; k < n; ++k) {
        Eigen::VectorXd qp = q, qm = q;
        qp[k] += h;
        qm[k] -= h;
        ForwardKinematics(robot, qp, &kp);
        ForwardKinematics(robot, qm, &km);
        ChainPoints(robot, kp, c, &pp);
        ChainPoints(robot, km, c, &pm);
        const Eigen::Matrix3Xd diff = (pp - pm) / (2 * h);
        dP_fd.col(k) = Eigen::Map<const Eigen::VectorXd>(diff.data(), 3 * size);
      }
      EXPECT_LT((dP - dP_fd).cwiseAbs().maxCoeff(), 1e-7) << robot.chains[c].name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, JacobianFd,
                         ::testing::Values("robots/lwr4_sdh.urdf", "robots/arm20_sdh.urdf",
                                           "robots/human_hand.urdf"));

TEST(Kinematics, PerStepPathDoesNotAllocate) {
  const Robot robot = LoadRobot(AssetFile("robots/arm20_sdh.urdf"));
  const int n = num_dofs(robot);
  KinematicsData kin(robot);
  const int chain = FindChain(robot, "arm");
  Eigen::MatrixXd J(3, n), F(6, n), dP(3 * ChainSize(robot, chain), n);
  Eigen::Matrix3Xd P(3, ChainSize(robot, chain));
  Eigen::VectorXd q = Eigen::VectorXd::Constant(n, 0.1);
  const long before = g_allocations.load();
  for (int step = 0; step < 10; ++step) {
    q[step] += 0.01;
    ForwardKinematics(robot, q, &kin);
    PointJacobian(robot, kin, 5, Eigen::Vector3d(0, 0, 0.1), J);
    AddPointJacobianAlong(robot, kin, 5, Eigen::Vector3d(0, 0, 0.1), Eigen::Vector3d::UnitX(), 1.0,
                          F.row(2));
    FrameJacobian(robot, kin, 7, F);
    ChainPoints(robot, kin, chain, &P);
    ChainJacobian(robot, kin, chain, dP);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
}

TEST(Kinematics, SizeChecksThrow) {
  const Robot robot = LoadRobot(AssetFile("robots/lwr4_sdh.urdf"));
  KinematicsData kin(robot);
  EXPECT_THROW(ForwardKinematics(robot, Eigen::VectorXd::Zero(3), &kin), std::invalid_argument);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot));
  q[2] = std::nan("");
  EXPECT_THROW(ForwardKinematics(robot, q, &kin), std::invalid_argument);
  Eigen::MatrixXd J(3, 2);
  EXPECT_THROW(PointJacobian(robot, kin, 1, Eigen::Vector3d::Zero(), J), std::invalid_argument);
  Eigen::MatrixXd J3(3, num_dofs(robot));
  EXPECT_THROW(PointJacobian(robot, kin, 999, Eigen::Vector3d::Zero(), J3), std::invalid_argument);
  const Eigen::Vector3d u = Eigen::Vector3d::UnitZ();
  EXPECT_THROW(AddPointJacobianAlong(robot, kin, 1, Eigen::Vector3d::Zero(), u, 1.0, J.row(0)),
               std::invalid_argument);
  EXPECT_THROW(AddPointJacobianAlong(robot, kin, 999, Eigen::Vector3d::Zero(), u, 1.0, J3.row(0)),
               std::invalid_argument);
}

TEST(Kinematics, ClosedChainRepeatsFirstPoint) {
  const Robot ring = LoadRobot(AssetFile("objects/ring.urdf"));
  KinematicsData kin(ring);
  ForwardKinematics(ring, Eigen::VectorXd(0), &kin);
  Eigen::Matrix3Xd p;
  ChainPoints(ring, kin, 0, &p);
  ASSERT_EQ(p.cols(), 25);
  EXPECT_TRUE(p.col(0).isApprox(p.col(24)));
  EXPECT_NEAR(p.col(6).norm(), 0.22, 1e-9);
}

TEST(Kinematics, HumanHandFingertipsAtZero) {
  const Robot robot = LoadRobot(AssetFile("robots/human_hand.urdf"));
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  // Middle finger (no splay): MCP at 0.446 HL, then (0.277 + 0.170 + 0.108) HL along z.
  const Eigen::Vector3d tip = kin.world_from_link[FindLink(robot, "middle_tip")].translation();
  EXPECT_NEAR(tip.z(), 0.19 * (0.446 + 0.277 + 0.170 + 0.108), 1e-12);
  EXPECT_NEAR(tip.x(), 0.0, 1e-12);
  // Flexion (positive) moves the fingertip towards the palm side (−y).
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot));
  q[7] = 0.5;  // index_mcp_flex
  ForwardKinematics(robot, q, &kin);
  EXPECT_LT(kin.world_from_link[FindLink(robot, "index_tip")].translation().y(), -0.02);
}

TEST(Kinematics, Arm20ZeroPoseIsACoilAroundTheRope) {
  const Robot robot = LoadRobot(AssetFile("robots/arm20_sdh.urdf"));
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  Eigen::Matrix3Xd arm;
  ChainPoints(robot, kin, FindChain(robot, "arm"), &arm);
  // The rope of the unwrapping scene (thesis §4.3.1): along world y at x = −0.1, z = 1.85. An
  // independent check winds the far ends of links 1..20 (≈ 872° at q = 0, ≈ 97° with q_i = −0.5
  // for i ≥ 2); our chain adds the near end of link 1 as point 0.
  topology::Axis rope;
  rope.point = Eigen::Vector3d(-0.1, 0, 1.85);
  rope.direction = Eigen::Vector3d::UnitY();
  const topology::Chain far_ends = arm.rightCols(20);
  EXPECT_NEAR(std::abs(topology::WindingNumber(far_ends, rope)) * 360.0, 872.35, 0.1);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot));
  q.segment(1, 19).setConstant(-0.5);
  ForwardKinematics(robot, q, &kin);
  ChainPoints(robot, kin, FindChain(robot, "arm"), &arm);
  const topology::Chain far_ends2 = arm.rightCols(20);
  EXPECT_NEAR(std::abs(topology::WindingNumber(far_ends2, rope)) * 360.0, 96.82, 0.1);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  ChainPoints(robot, kin, FindChain(robot, "arm"), &arm);
  // First link starts at the top of the stem.
  EXPECT_TRUE(arm.col(0).isApprox(Eigen::Vector3d(0, 0, 2)));
}

}  // namespace
}  // namespace planning
