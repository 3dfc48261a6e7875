#include "topology/writhe_stream.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "tests/topology/test_chains.h"

namespace topology {
namespace {

using testing::HopfA;
using testing::HopfB;
using testing::RandomChain;
using testing::TorusLinkComponent;

Chain Random(int n, unsigned seed, const Eigen::Vector3d& origin) {
  std::mt19937 rng(seed);
  return RandomChain(n, 0.1, origin, &rng);
}

// One entry of W in long double (the same closed form, ~2000× smaller rounding): the reference
// for the error bound.
long double ReferenceEntry(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                           const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  using V = Eigen::Matrix<long double, 3, 1>;
  auto dir = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    const V r = q.cast<long double>() - p.cast<long double>();
    return V(r / r.norm());
  };
  const V v1 = dir(a0, b0), v2 = dir(a0, b1), v3 = dir(a1, b1), v4 = dir(a1, b0);
  const long double x1 = 1 + v1.dot(v2) + v2.dot(v3) + v3.dot(v1), y1 = v1.dot(v2.cross(v3));
  const long double x2 = 1 + v3.dot(v1) + v3.dot(v4) + v4.dot(v1), y2 = v1.dot(v3.cross(v4));
  return -std::atan2(x1 * y2 + y1 * x2, x1 * x2 - y1 * y2) / (2 * 3.14159265358979323846264L);
}

TEST(WritheStreamTest, TotalAndRowSumsEqualTheMatrix) {
  int case_index = 0;
  for (const auto& [na, nb] : {std::pair{2, 2}, {2, 300}, {300, 2}, {120, 77}, {600, 500}}) {
    const Chain a = Random(na, 10 + case_index, {0, 0, 0});
    const Chain b = Random(nb, 20 + case_index, {0.05, 0, 0});
    ++case_index;
    for (WritheVariant v : {WritheVariant::kSigned, WritheVariant::kUnsignedSolidAngle}) {
      WritheStreamOptions o;
      o.writhe.variant = v;
      o.row_sums = true;
      const Eigen::MatrixXd w = WritheMatrix(a, b, o.writhe);
      const WritheSums s = StreamWritheSums(a, b, o);
      EXPECT_EQ(s.rows, na - 1);
      EXPECT_EQ(s.cols, nb - 1);
      const double scale = std::max(1.0, w.cwiseAbs().sum());
      EXPECT_LE(std::abs(s.total - w.sum()), 1e-12 * scale) << na << "x" << nb;
      EXPECT_NEAR(s.abs_total, w.cwiseAbs().sum(), 1e-12 * scale);
      ASSERT_EQ(s.row_sums.size(), na - 1);
      EXPECT_LE((s.row_sums - w.rowwise().sum()).cwiseAbs().maxCoeff(), 1e-12 * scale);
    }
  }
}

TEST(WritheStreamTest, ResultIsBitwiseTheSameForAnyThreadCount) {
  const Chain a = Random(700, 1, {0, 0, 0}), b = Random(650, 2, {0.05, 0, 0});  // > 2e5 pairs
  WritheStreamOptions o;
  o.row_sums = true;
  o.threads = 1;
  const WritheSums one = StreamWritheSums(a, b, o);
  for (int threads : {2, 3, 8}) {
    o.threads = threads;
    const WritheSums s = StreamWritheSums(a, b, o);
    EXPECT_EQ(s.total, one.total) << threads;
    EXPECT_EQ(s.error_bound, one.error_bound) << threads;
    EXPECT_TRUE(s.row_sums == one.row_sums) << threads;
  }
}

TEST(WritheStreamTest, ErrorBoundHoldsAgainstLongDouble) {
  // Random chains starting 0.02 apart (step 0.1): many close, ill-conditioned pairs.
  for (unsigned seed = 0; seed < 4; ++seed) {
    const Chain a = Random(150, 100 + seed, {0, 0, 0}), b = Random(140, 200 + seed, {0.02, 0, 0});
    long double exact = 0;
    for (int i = 0; i + 1 < a.cols(); ++i) {
      for (int j = 0; j + 1 < b.cols(); ++j) {
        exact += ReferenceEntry(a.col(i), a.col(i + 1), b.col(j), b.col(j + 1));
      }
    }
    const WritheSums s = StreamWritheSums(a, b);
    EXPECT_EQ(s.degenerate_pairs, 0);
    EXPECT_LE(std::abs(static_cast<long double>(s.total) - exact), s.error_bound) << seed;
    EXPECT_LT(s.error_bound, 1e-9);  // and the bound is not vacuous
  }
}

TEST(WritheStreamTest, ProgressReportsEveryPairAndCanStop) {
  const Chain a = Random(800, 3, {0, 0, 0}), b = Random(800, 4, {0.05, 0, 0});
  WritheStreamOptions o;
  long long last = 0, total = 0;
  o.progress = [&](long long done, long long all) {
    EXPECT_GE(done, last);
    last = done;
    total = all;
  };
  o.threads = 1;
  StreamWritheSums(a, b, o);
  EXPECT_EQ(last, 799LL * 799);
  EXPECT_EQ(total, 799LL * 799);
  o.threads = 2;
  o.progress = [](long long, long long) { throw std::runtime_error("stop"); };
  EXPECT_THROW(StreamWritheSums(a, b, o), std::runtime_error);
}

TEST(WritheStreamTest, BlockSumsAddUpToTheMatrix) {
  const Chain a = Random(301, 5, {0, 0, 0}), b = Random(251, 6, {0.05, 0, 0});
  const Eigen::MatrixXd w = WritheMatrix(a, b);
  const WritheBlockSums one = BlockWritheSums(a, b, 1000, 1000);  // blocks of one segment: W
  EXPECT_EQ(one.row_block, 1);
  EXPECT_LE((one.sums - w).cwiseAbs().maxCoeff(), 0.0);
  const WritheBlockSums s = BlockWritheSums(a, b, 7, 16);
  EXPECT_EQ(s.row_block, 43);  // ⌈300/7⌉
  EXPECT_EQ(s.col_block, 16);  // ⌈250/16⌉
  ASSERT_EQ(s.sums.rows(), 7);
  ASSERT_EQ(s.sums.cols(), 16);
  EXPECT_NEAR(s.sums.sum(), w.sum(), 1e-12 * w.cwiseAbs().sum());
  for (int p = 0; p < 7; ++p) {
    for (int q = 0; q < 16; ++q) {
      const int i0 = p * 43, j0 = q * 16;
      const int ni = std::min(300, i0 + 43) - i0, nj = std::min(250, j0 + 16) - j0;
      EXPECT_NEAR(s.sums(p, q), w.block(i0, j0, ni, nj).sum(), 1e-13) << p << "," << q;
    }
  }
  EXPECT_THROW(BlockWritheSums(a, b, 0, 4), std::invalid_argument);
}

TEST(WritheStreamTest, LinkingNumbersOfKnownLinks) {
  const LinkingResult hopf = LinkingNumber(HopfA(64), HopfB(64));
  EXPECT_EQ(hopf.status, LinkingStatus::kCertified);
  EXPECT_EQ(hopf.linking_number, -1);
  EXPECT_LE(hopf.distance, hopf.error_bound);
  for (int k = 1; k <= 4; ++k) {  // as WritheTest.TorusLinksGiveLinkingNumberK
    const LinkingResult r =
        LinkingNumber(TorusLinkComponent(k, 0, 48 * k), TorusLinkComponent(k, 1, 48 * k));
    EXPECT_EQ(r.status, LinkingStatus::kCertified) << k;
    EXPECT_EQ(std::abs(r.linking_number), k);
  }
  Chain far = HopfB(48);
  far.row(0).array() += 3.0;
  const LinkingResult unlinked = LinkingNumber(HopfA(48), far);
  EXPECT_EQ(unlinked.status, LinkingStatus::kCertified);
  EXPECT_EQ(unlinked.linking_number, 0);
  EXPECT_STREQ(LinkingStatusName(unlinked.status), "certified");
}

TEST(WritheStreamTest, LinkingNumberOfALongCurveIsCertified) {
  const int n = 8000;  // 6.4·10⁷ pairs of a (2, 6) torus link
  const LinkingResult r = LinkingNumber(TorusLinkComponent(3, 0, n), TorusLinkComponent(3, 1, n));
  EXPECT_EQ(r.status, LinkingStatus::kCertified);
  EXPECT_EQ(std::abs(r.linking_number), 3);
  EXPECT_LT(r.error_bound, 1e-4);
}

TEST(WritheStreamTest, TouchingCurvesAreNotRounded) {
  Chain b = HopfB(64);
  b.row(0).array() -= 1.0;  // passes through (−1, 0, 0), a vertex of A
  const LinkingResult r = LinkingNumber(HopfA(64), b);
  EXPECT_NE(r.status, LinkingStatus::kCertified);
}

TEST(WritheStreamTest, LinkingRefusesOpenChains) {
  const Chain closed = HopfA(16);
  const Chain open = closed.leftCols(16);
  try {
    LinkingNumber(closed, open);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("chain B is not closed"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(IsClosedChain(open));
  EXPECT_TRUE(IsClosedChain(closed));
  EXPECT_THROW(LinkingNumber(Chain(3, 1), closed), std::invalid_argument);
}

TEST(WritheStreamTest, NearlyClosedChainsAreSnappedShut) {
  Chain a = HopfA(64), b = HopfB(64);
  a(1, 64) = -2.4e-16;  // sin(2π) in floating point, as numpy.linspace(0, 2π) gives
  EXPECT_TRUE(IsClosedChain(a));
  const LinkingResult r = LinkingNumber(a, b);
  EXPECT_EQ(r.status, LinkingStatus::kCertified);
  EXPECT_EQ(r.linking_number, -1);
  a(1, 64) = 1e-6;  // a real gap
  EXPECT_FALSE(IsClosedChain(a));
}

}  // namespace
}  // namespace topology
