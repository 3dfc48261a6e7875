// Property battery over every Feature (feature_factory.cc): dim() consistency, no NaN, and the
// analytic Jacobian against central differences at seeded random configurations.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "planning/robot/kinematics.h"
#include "tests/planning/features/feature_factory.h"
#include "topology/writhe.h"

namespace planning::testing {
namespace {

class FeatureJacobianTest : public ::testing::TestWithParam<int> {};

Eigen::VectorXd RandomConfiguration(const Robot& robot, std::mt19937* rng) {
  const Eigen::VectorXd lo = LowerLimits(robot), hi = UpperLimits(robot);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::VectorXd q(num_dofs(robot));
  for (int k = 0; k < q.size(); ++k) {
    const double l = std::isfinite(lo[k]) ? lo[k] : -M_PI, h = std::isfinite(hi[k]) ? hi[k] : M_PI;
    q[k] = l + (0.1 + 0.8 * u(*rng)) * (h - l);
  }
  return q;
}

TEST_P(FeatureJacobianTest, MatchesCentralDifferences) {
  const FeatureFixture& f = SharedFixture();
  std::vector<FeatureCase> cases = AllFeatureCases(f);
  const FeatureCase& c = cases[GetParam()];
  SCOPED_TRACE(c.name);
  const Robot& robot = f.robot;
  const int n = num_dofs(robot), m = c.feature->dim();
  ASSERT_GT(m, 0);
  EXPECT_FALSE(c.feature->name().empty());
  auto data = c.feature->CreateData(robot);
  KinematicsData kin(robot);
  Eigen::VectorXd y(m), yp(m), ym(m);
  Eigen::MatrixXd J(m, n), Jfd(m, n);
  std::mt19937 rng(1234 + GetParam());
  // FCL's GJK distances are accurate to ~1e-9 m only: larger steps and a looser tolerance there.
  const bool fcl = c.name == "collision";
  const double h = fcl ? 1e-4 : 1e-6;
  const double tol = fcl ? 2e-3 : 1e-5;
  int checked = 0, active = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const Eigen::VectorXd q = RandomConfiguration(robot, &rng);
    ForwardKinematics(robot, q, &kin);
    c.feature->Eval(robot, kin, data.get(), y, &J);
    ASSERT_TRUE(y.allFinite()) << "trial " << trial;
    ASSERT_TRUE(J.allFinite()) << "trial " << trial;
    // Value without the Jacobian is the same.
    Eigen::VectorXd y2(m);
    c.feature->Eval(robot, kin, data.get(), y2, nullptr);
    EXPECT_LT((y2 - y).lpNorm<Eigen::Infinity>(), 1e-12);
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      ForwardKinematics(robot, qp, &kin);
      c.feature->Eval(robot, kin, data.get(), yp, nullptr);
      ForwardKinematics(robot, qm, &kin);
      c.feature->Eval(robot, kin, data.get(), ym, nullptr);
      Jfd.col(k) = (yp - ym) / (2 * h);
    }
    const double scale = std::max(1.0, Jfd.lpNorm<Eigen::Infinity>());
    // Hinges and FCL distances can switch pair sets within ±h: skip such (rare) trials.
    const bool kink = (c.name == "collision" || c.name == "joint_limits" || c.name == "box" ||
                       c.name == "line_clearance") &&
                      (J - Jfd).lpNorm<Eigen::Infinity>() > 5 * tol * scale;
    if (kink) {
      if (getenv("FD_DEBUG"))
        std::cerr << c.name << " trial " << trial << " diff " << (J - Jfd).lpNorm<Eigen::Infinity>()
                  << " y " << y.transpose() << "\nJ\n"
                  << J << "\nFD\n"
                  << Jfd << std::endl;
      continue;
    }
    EXPECT_LT((J - Jfd).lpNorm<Eigen::Infinity>(), tol * scale) << "trial " << trial << "\nJ =\n"
                                                                << J << "\nFD =\n"
                                                                << Jfd;
    ++checked;
    active += J.lpNorm<Eigen::Infinity>() > 0 ? 1 : 0;
  }
  EXPECT_GE(checked, 4);
  EXPECT_GE(active, 1) << "the feature was never active: the test checks nothing";
}

INSTANTIATE_TEST_SUITE_P(AllFeatures, FeatureJacobianTest, ::testing::Range(0, NumFeatureCases()),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return AllFeatureCases(SharedFixture())[info.param].name;
                         });

// Closed by its chord, the writhe feature is the open one of the chain with its first point
// appended: one more row (the chord's), and the matrix's other rows unchanged.
TEST(Features, WritheClosedByChordAppendsTheChord) {
  const FeatureFixture& f = SharedFixture();
  const Robot& r = f.robot;
  const int arm = FindChain(r, "arm");
  const Eigen::Matrix3Xd ring = ObjectChainPoints(f.env, FindObject(f.env, "ring"), 0);
  const auto open = MakeWritheFeature(r, arm, ring, WritheOutput::kMatrix);
  const auto closed = MakeWritheFeature(r, arm, ring, WritheOutput::kMatrix, true);
  const auto closed_total = MakeWritheFeature(r, arm, ring, WritheOutput::kTotal, true);
  const int cols = static_cast<int>(ring.cols()) - 1;
  ASSERT_EQ(closed->dim(), open->dim() + cols);
  Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(num_dofs(r), -0.4, 0.5);
  KinematicsData kin(r);
  ForwardKinematics(r, q, &kin);
  Eigen::Matrix3Xd P;
  ChainPoints(r, kin, arm, &P);
  Eigen::Matrix3Xd loop(3, P.cols() + 1);
  loop << P, P.col(0);
  const Eigen::MatrixXd W = topology::WritheMatrix(loop, ring);
  Eigen::VectorXd y_open(open->dim()), y(closed->dim()), total(1);
  auto d_open = open->CreateData(r);
  auto d = closed->CreateData(r);
  auto d_total = closed_total->CreateData(r);
  open->Eval(r, kin, d_open.get(), y_open, nullptr);
  closed->Eval(r, kin, d.get(), y, nullptr);
  closed_total->Eval(r, kin, d_total.get(), total, nullptr);
  EXPECT_LT((y.head(open->dim()) - y_open).lpNorm<Eigen::Infinity>(), 1e-15);
  for (int j = 0; j < cols; ++j) EXPECT_NEAR(y[open->dim() + j], W(W.rows() - 1, j), 1e-15);
  EXPECT_NEAR(total[0], W.sum(), 1e-12);
}

TEST(Features, BadArgumentsThrow) {
  const FeatureFixture& f = SharedFixture();
  EXPECT_THROW(MakePositionFeature(f.robot, 999, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(MakeWritheFeature(f.robot, 0, Eigen::Matrix3Xd(3, 1), WritheOutput::kTotal),
               std::invalid_argument);
  EXPECT_THROW(MakeCollisionFeature(f.robot, f.env, {}, 0.0), std::invalid_argument);
  EXPECT_THROW(MakeLineClearanceFeature(f.robot, 0, topology::Axis{}, 0.0), std::invalid_argument);
  topology::Axis no_direction;
  no_direction.direction.setZero();
  EXPECT_THROW(MakeLineClearanceFeature(f.robot, 0, no_direction, 0.1), std::invalid_argument);
  EXPECT_THROW(MakeBoxFeature(f.robot, 0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                              Eigen::Vector3d::Constant(0.01), 0.02),
               std::invalid_argument);
}

}  // namespace
}  // namespace planning::testing
