#include "topology/writhe.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "tests/topology/test_chains.h"

namespace topology {
namespace {

using testing::Helix;
using testing::HopfA;
using testing::HopfB;
using testing::RandomChain;
using testing::TorusLinkComponent;

// ---------------------------------------------------------------------------------------------
// Known links and helices.

TEST(WritheTest, PinnedHopfLinkTotalIsMinusOne) {
  const Eigen::MatrixXd w = WritheMatrix(HopfA(64), HopfB(64));
  EXPECT_EQ(w.rows(), 64);
  EXPECT_EQ(w.cols(), 64);
  EXPECT_NEAR(w.sum(), -1.0, 1e-9);
}

TEST(WritheTest, HopfLinkIsIntegerAtAnyResolution) {
  for (int n : {8, 13, 32, 200}) EXPECT_NEAR(TotalWrithe(HopfA(n), HopfB(n + 3)), -1.0, 1e-9) << n;
}

TEST(WritheTest, UnlinkedRingsTotalZero) {
  Chain b = HopfB(48);
  b.row(0).array() += 3.0;  // move the second ring away: no longer linked
  EXPECT_NEAR(TotalWrithe(HopfA(48), b), 0.0, 1e-9);
}

TEST(WritheTest, TorusLinksGiveLinkingNumberK) {
  for (int k = 1; k <= 4; ++k) {
    const double total =
        TotalWrithe(TorusLinkComponent(k, 0, 48 * k), TorusLinkComponent(k, 1, 48 * k));
    EXPECT_NEAR(std::abs(total), k, 1e-8) << "k=" << k;
    EXPECT_NEAR(total, std::round(total), 1e-8);
  }
}

TEST(WritheTest, HelixAroundLongPoleCountsTurns) {
  Chain pole(3, 2);
  pole << 0, 0, 0, 0, -50, 50;
  for (double k : {0.5, 1.0, 1.5, 2.0, 3.0}) {
    const double total = TotalWrithe(Helix(k, 0.3, 0.3 * k, static_cast<int>(60 * k)), pole);
    EXPECT_NEAR(std::abs(total), k, 0.01) << "turns=" << k;
  }
}

// ---------------------------------------------------------------------------------------------
// Symmetries.

class WritheRandomTest : public ::testing::Test {
 protected:
  std::mt19937 rng_{12345};
  Chain a_ = RandomChain(9, 0.4, Eigen::Vector3d(0, 0, 0), &rng_);
  Chain b_ = RandomChain(7, 0.4, Eigen::Vector3d(0.3, 0.2, 0.1), &rng_);
};

TEST_F(WritheRandomTest, InvariantUnderRigidMotionAndScaling) {
  const Eigen::MatrixXd w = WritheMatrix(a_, b_);
  Eigen::Affine3d t = Eigen::Translation3d(1.5, -2.0, 0.7) *
                      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()) *
                      Eigen::Scaling(2.5);
  const Eigen::MatrixXd wt = WritheMatrix(t * a_, t * b_);
  EXPECT_LT((w - wt).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::MatrixXd ws = WritheMatrix(1e-3 * a_, 1e-3 * b_);
  EXPECT_LT((w - ws).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(w.cwiseAbs().maxCoeff(), 1e-3);  // the test says something
}

TEST_F(WritheRandomTest, ReflectionFlipsSign) {
  const Eigen::Matrix3d mirror = Eigen::Vector3d(1, -1, 1).asDiagonal();
  const Eigen::MatrixXd w = WritheMatrix(a_, b_);
  const Eigen::MatrixXd wr = WritheMatrix(mirror * a_, mirror * b_);
  EXPECT_LT((w + wr).cwiseAbs().maxCoeff(), 1e-12);
}

TEST_F(WritheRandomTest, SwappingChainsTransposes) {
  const Eigen::MatrixXd w = WritheMatrix(a_, b_);
  const Eigen::MatrixXd wt = WritheMatrix(b_, a_);
  EXPECT_LT((w - wt.transpose()).cwiseAbs().maxCoeff(), 1e-13);
}

TEST_F(WritheRandomTest, ReversingOneChainFlipsSign) {
  const Eigen::MatrixXd w = WritheMatrix(a_, b_);
  const Eigen::MatrixXd wr = WritheMatrix(a_.rowwise().reverse(), b_);
  EXPECT_LT((w + wr.colwise().reverse()).cwiseAbs().maxCoeff(), 1e-13);
}

TEST_F(WritheRandomTest, UnsignedVariantIsFourPiAbs) {
  WritheOptions o;
  o.variant = WritheVariant::kUnsignedSolidAngle;
  const Eigen::MatrixXd w = WritheMatrix(a_, b_);
  const Eigen::MatrixXd u = WritheMatrix(a_, b_, o);
  EXPECT_LT((u - 4 * M_PI * w.cwiseAbs()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GE(u.minCoeff(), 0.0);
  EXPECT_LT(u.maxCoeff(), 2 * M_PI);
}

// ---------------------------------------------------------------------------------------------
// Closed form against Gauss–Legendre quadrature of the defining double integral.

// Nodes and weights of n-point Gauss–Legendre on [0, 1] (Newton on P_n).
void GaussLegendre(int n, std::vector<double>* x, std::vector<double>* w) {
  x->resize(n);
  w->resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    (*x)[i] = 0.5 * (1 - z);
    (*w)[i] = 1.0 / ((1 - z * z) * dp * dp);
  }
}

// (1/4π) ∫∫ ((a − b)·(da × db))/|a − b|³ over a0→a1 and b0→b1, composite GL with `panels`².
double QuadratureWrithe(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  std::vector<double> x, w;
  GaussLegendre(20, &x, &w);
  const int panels = 8;
  const Eigen::Vector3d da = a1 - a0, db = b1 - b0;
  double sum = 0;
  for (int pi = 0; pi < panels; ++pi) {
    for (int pj = 0; pj < panels; ++pj) {
      for (size_t i = 0; i < x.size(); ++i) {
        for (size_t j = 0; j < x.size(); ++j) {
          const double s = (pi + x[i]) / panels, t = (pj + x[j]) / panels;
          const Eigen::Vector3d r = (a0 + s * da) - (b0 + t * db);
          sum += w[i] * w[j] * r.dot(da.cross(db)) / std::pow(r.norm(), 3);
        }
      }
    }
  }
  return sum / (panels * panels) / (4 * M_PI);
}

TEST(WritheTest, ClosedFormMatchesQuadrature) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto rnd = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  int checked = 0;
  while (checked < 40) {
    const Eigen::Vector3d a0 = rnd(), a1 = rnd(), b0 = rnd(), b1 = rnd();
    // Keep pairs whose segments stay apart, where quadrature converges to 1e-9.
    double min_dist = 1e9;
    for (int i = 0; i <= 50; ++i) {
      for (int j = 0; j <= 50; ++j) {
        min_dist =
            std::min(min_dist, ((a0 + (a1 - a0) * i / 50.0) - (b0 + (b1 - b0) * j / 50.0)).norm());
      }
    }
    if (min_dist < 0.25) continue;
    ++checked;
    const double exact = SegmentPairWrithe(a0, a1, b0, b1);
    EXPECT_NEAR(exact, QuadratureWrithe(a0, a1, b0, b1), 1e-9) << "pair " << checked;
  }
}

// ---------------------------------------------------------------------------------------------
// Jacobians against central finite differences.

TEST_F(WritheRandomTest, JacobianMatchesFiniteDifferences) {
  for (WritheVariant variant : {WritheVariant::kSigned, WritheVariant::kUnsignedSolidAngle}) {
    WritheOptions opt;
    opt.variant = variant;
    Eigen::MatrixXd w;
    WritheJacobian jac;
    WritheWorkspace ws;
    WritheMatrixWithJacobian(a_, b_, opt, &w, &jac, &ws);
    EXPECT_LT((w - WritheMatrix(a_, b_, opt)).cwiseAbs().maxCoeff(), 1e-15);
    const double h = 1e-6;
    double worst = 0;
    for (int which = 0; which < 2; ++which) {
      const Chain& base = which == 0 ? a_ : b_;
      for (int p = 0; p < base.cols(); ++p) {
        for (int c = 0; c < 3; ++c) {
          Chain plus = base, minus = base;
          plus(c, p) += h;
          minus(c, p) -= h;
          const Eigen::MatrixXd fd =
              (which == 0 ? WritheMatrix(plus, b_, opt) - WritheMatrix(minus, b_, opt)
                          : WritheMatrix(a_, plus, opt) - WritheMatrix(a_, minus, opt)) /
              (2 * h);
          for (int i = 0; i < jac.rows; ++i) {
            for (int j = 0; j < jac.cols; ++j) {
              const auto g = jac.pair.col(i * jac.cols + j);
              double analytic = 0;
              if (which == 0) {
                if (p == i) analytic = g(c);
                if (p == i + 1) analytic = g(3 + c);
              } else {
                if (p == j) analytic = g(6 + c);
                if (p == j + 1) analytic = g(9 + c);
              }
              worst = std::max(worst, std::abs(analytic - fd(i, j)));
            }
          }
        }
      }
    }
    EXPECT_LT(worst, 1e-7) << "variant " << static_cast<int>(variant);
  }
}

TEST_F(WritheRandomTest, TotalGradientAndChainRuleMatchFiniteDifferences) {
  // Points move linearly with 5 parameters: P(q) = P0 + Σ q_k D_k.
  const int nq = 5;
  std::normal_distribution<double> g(0, 1);
  Eigen::MatrixXd da_dq(3 * a_.cols(), nq), db_dq(3 * b_.cols(), nq);
  for (int i = 0; i < da_dq.size(); ++i) da_dq.data()[i] = g(rng_);
  for (int i = 0; i < db_dq.size(); ++i) db_dq.data()[i] = g(rng_);
  auto at = [&](const Eigen::VectorXd& q, const Chain& base, const Eigen::MatrixXd& d) {
    Eigen::VectorXd flat = Eigen::Map<const Eigen::VectorXd>(base.data(), base.size()) + d * q;
    return Chain(Eigen::Map<Chain>(flat.data(), 3, base.cols()));
  };
  Eigen::MatrixXd w, jq;
  WritheJacobian jac;
  WritheWorkspace ws;
  WritheMatrixWithJacobian(a_, b_, {}, &w, &jac, &ws);
  ChainWritheJacobian(jac, da_dq, db_dq, &jq);
  ASSERT_EQ(jq.rows(), w.size());
  ASSERT_EQ(jq.cols(), nq);
  const double h = 1e-6;
  for (int k = 0; k < nq; ++k) {
    Eigen::VectorXd qp = Eigen::VectorXd::Zero(nq), qm = qp;
    qp(k) = h;
    qm(k) = -h;
    const Eigen::MatrixXd fd = (WritheMatrix(at(qp, a_, da_dq), at(qp, b_, db_dq)) -
                                WritheMatrix(at(qm, a_, da_dq), at(qm, b_, db_dq))) /
                               (2 * h);
    for (int i = 0; i < w.rows(); ++i) {
      for (int j = 0; j < w.cols(); ++j) EXPECT_NEAR(jq(i * w.cols() + j, k), fd(i, j), 1e-6);
    }
  }
  // Static B: an empty db_dq.
  Eigen::MatrixXd ja;
  ChainWritheJacobian(jac, da_dq, Eigen::MatrixXd(), &ja);
  Eigen::Matrix3Xd ga, gb;
  WeightedWritheGradient(jac, Eigen::MatrixXd(), &ga, &gb);
  const Eigen::RowVectorXd total_dq =
      Eigen::Map<const Eigen::RowVectorXd>(ga.data(), ga.size()) * da_dq;
  EXPECT_LT((ja.colwise().sum() - total_dq).cwiseAbs().maxCoeff(), 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Degenerate input: finite, zero, zero gradient.

TEST(WritheTest, DegeneratePairsGiveZeroAndZeroGradient) {
  const Eigen::Vector3d o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  struct Case {
    const char* what;
    Eigen::Vector3d a0, a1, b0, b1;
  };
  const Case cases[] = {
      {"zero-length A", o, o, y, y + z},
      {"zero-length B", o, x, y, y},
      {"shared endpoint", o, x, x, x + y},
      {"touching (endpoint on segment)", o, x, 0.5 * x, 0.5 * x + z},
      {"collinear disjoint", o, x, 2 * x, 3 * x},
      {"collinear overlapping", o, 2 * x, x, 3 * x},
      {"coplanar crossing", -x, x, -y, y},
      {"coplanar parallel", o, x, y, x + y},
      {"identical", o, x, o, x},
  };
  for (const Case& c : cases) {
    SegmentPairGradient g;
    const double w = SegmentPairWrithe(c.a0, c.a1, c.b0, c.b1, {}, &g);
    EXPECT_EQ(w, 0.0) << c.what;
    for (const Eigen::Vector3d* v : {&g.d_a0, &g.d_a1, &g.d_b0, &g.d_b1}) {
      EXPECT_TRUE(v->allFinite()) << c.what;
    }
  }
}

TEST(WritheTest, NearCrossingIsFiniteAndBounded) {
  for (double eps : {1e-3, 1e-6, 1e-9, 1e-12, 1e-15}) {
    SegmentPairGradient g;
    const double w = SegmentPairWrithe({-1, 0, 0}, {1, 0, 0}, {0, -1, eps}, {0, 1, eps}, {}, &g);
    EXPECT_TRUE(std::isfinite(w));
    EXPECT_LE(std::abs(w), 0.5);
    EXPECT_TRUE(g.d_a0.allFinite() && g.d_b1.allFinite());
  }
}

TEST(WritheTest, RejectsBadChains) {
  Chain one(3, 1);
  one.setZero();
  Chain two(3, 2);
  two << 0, 1, 0, 0, 0, 0;
  EXPECT_THROW(WritheMatrix(one, two), std::invalid_argument);
  two(0, 1) = std::nan("");
  EXPECT_THROW(WritheMatrix(two, two), std::invalid_argument);
}

TEST(WritheTest, LinkingNumberIsScaleInvariantUpToTheCoordinateLimit) {
  // From 1e-6 up to 1e99 (inside kMaxCoordinate) the Hopf link links −1; beyond it the chains are
  // refused instead of their squared lengths overflowing to inf/NaN. (Below ~1e-11 the absolute
  // degeneracy tolerance of the pair formula treats every pair as degenerate.)
  for (double s : {1e-6, 1e-3, 1e3, 1e99}) {
    EXPECT_NEAR(TotalWrithe(s * HopfA(32), s * HopfB(35)), -1.0, 1e-9) << s;
  }
  try {
    TotalWrithe(HopfA(32), 1e155 * HopfB(35));
    ADD_FAILURE() << "1e155 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "writhe: chain B has a coordinate beyond ±1e100 (squared lengths would overflow)");
  }
}

TEST(WritheTest, SelfWritheOfPlanarCurveIsZeroAndMirrorFlips) {
  EXPECT_NEAR(SelfWrithe(HopfA(32)), 0.0, 1e-12);
  const Chain h = Helix(3, 0.3, 1.0, 90);
  const double s = SelfWrithe(h);
  EXPECT_GT(std::abs(s), 0.1);
  const Eigen::Matrix3d mirror = Eigen::Vector3d(1, 1, -1).asDiagonal();
  EXPECT_NEAR(SelfWrithe(mirror * h), -s, 1e-12);
  // The definition: 2 Σ_{i<j} W_ij over non-adjacent pairs.
  const Eigen::MatrixXd w = WritheMatrix(h, h);
  double sum = 0;
  for (int i = 0; i < w.rows(); ++i)
    for (int j = i + 2; j < w.cols(); ++j) sum += w(i, j);
  EXPECT_NEAR(s, 2 * sum, 1e-12);
}

}  // namespace
}  // namespace topology
