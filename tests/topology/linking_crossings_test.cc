#include "topology/linking_crossings.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>

#include "tests/topology/test_chains.h"

namespace topology {
namespace {

using testing::ClosedCurve;
using testing::HopfA;
using testing::HopfB;
using testing::TorusLinkComponent;

// A closed random polygon: n points of a random walk, closed by repeating the first.
Chain RandomClosed(int n, double step, const Eigen::Vector3d& origin, std::mt19937* rng) {
  std::normal_distribution<double> g(0.0, step);
  Chain c(3, n + 1);
  c.col(0) = origin;
  for (int k = 1; k < n; ++k) c.col(k) = c.col(k - 1) + Eigen::Vector3d(g(*rng), g(*rng), g(*rng));
  c.col(n) = c.col(0);
  return c;
}

Chain Reversed(const Chain& c) { return c.rowwise().reverse(); }

TEST(CrossingLinkingTest, KnownLinksMatchTheGaussIntegral) {
  const LinkingResult hopf = CrossingLinkingNumber(HopfA(64), HopfB(64));
  ASSERT_EQ(hopf.status, LinkingStatus::kCertified);
  EXPECT_EQ(hopf.method, LinkingMethod::kCrossings);
  EXPECT_EQ(hopf.linking_number, LinkingNumber(HopfA(64), HopfB(64)).linking_number);
  EXPECT_EQ(std::abs(hopf.linking_number), 1);
  EXPECT_TRUE(std::isnan(hopf.gauss_integral));
  for (int k = 1; k <= 5; ++k) {
    const Chain a = TorusLinkComponent(k, 0, 48 * k), b = TorusLinkComponent(k, 1, 48 * k);
    const LinkingResult r = CrossingLinkingNumber(a, b);
    const LinkingResult g = LinkingNumber(a, b);
    ASSERT_EQ(r.status, LinkingStatus::kCertified) << k;
    ASSERT_EQ(g.status, LinkingStatus::kCertified) << k;
    EXPECT_EQ(r.linking_number, g.linking_number) << k;
    EXPECT_EQ(std::abs(r.linking_number), k);
    EXPECT_GE(r.crossings, 2 * k);
    EXPECT_EQ(r.crossings % 2, 0);
  }
}

TEST(CrossingLinkingTest, SymmetriesOfTheLinkingNumber) {
  const Chain a = TorusLinkComponent(3, 0, 150), b = TorusLinkComponent(3, 1, 150);
  const long long lk = CrossingLinkingNumber(a, b).linking_number;
  EXPECT_EQ(CrossingLinkingNumber(b, a).linking_number, lk);             // symmetric
  EXPECT_EQ(CrossingLinkingNumber(Reversed(a), b).linking_number, -lk);  // orientation
  EXPECT_EQ(CrossingLinkingNumber(a, Reversed(b)).linking_number, -lk);
  // A mirror image negates it.
  Chain ma = a, mb = b;
  ma.row(0) *= -1.0;
  mb.row(0) *= -1.0;
  EXPECT_EQ(CrossingLinkingNumber(ma, mb).linking_number, -lk);
}

// Randomly rotated, perturbed torus links and pairs of random closed walks: wherever the Gauss
// integral is certified, the crossings are too and give the same integer.
TEST(CrossingLinkingTest, AgreesWithTheGaussIntegralOnRandomCurves) {
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0, linked = 0;
  for (int trial = 0; trial < 120; ++trial) {
    Chain a, b;
    if (trial % 2 == 0) {
      const int k = 1 + trial % 5;
      a = TorusLinkComponent(k, 0, 40 * k);
      b = TorusLinkComponent(k, 1, 40 * k);
      const Eigen::Matrix3d rot =
          Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)))
              .normalized()
              .toRotationMatrix();
      for (Chain* c : {&a, &b}) {
        *c = rot * *c;
        for (int p = 0; p + 1 < c->cols(); ++p) {
          c->col(p) += 0.05 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
        }
        c->col(c->cols() - 1) = c->col(0);
      }
    } else {
      a = RandomClosed(30 + trial, 0.3, Eigen::Vector3d::Zero(), &rng);
      b = RandomClosed(25 + trial, 0.3, Eigen::Vector3d(0.2, 0.1, 0.0), &rng);
    }
    const LinkingResult g = LinkingNumber(a, b);
    if (g.status != LinkingStatus::kCertified) continue;
    const LinkingResult r = CrossingLinkingNumber(a, b);
    ASSERT_EQ(r.status, LinkingStatus::kCertified) << trial;
    EXPECT_EQ(r.linking_number, g.linking_number) << trial;
    ++compared;
    linked += r.linking_number != 0;
  }
  EXPECT_GE(compared, 110);
  EXPECT_GE(linked, 60);
}

// Symmetric inputs (vertices on the coordinate planes, both torus components at the same
// azimuths, the Hopf link of test_chains.h) are not degenerate for the generic directions: the
// first one answers.
TEST(CrossingLinkingTest, SymmetricInputsUseTheFirstDirection) {
  for (int n : {4, 8, 64}) {
    const LinkingResult r = CrossingLinkingNumber(HopfA(n), HopfB(n));
    ASSERT_EQ(r.status, LinkingStatus::kCertified) << n;
    EXPECT_EQ(r.linking_number, LinkingNumber(HopfA(n), HopfB(n)).linking_number);
  }
  const LinkingResult t =
      CrossingLinkingNumber(TorusLinkComponent(3, 0, 96), TorusLinkComponent(3, 1, 96));
  ASSERT_EQ(t.status, LinkingStatus::kCertified);
  EXPECT_GT(t.projection.norm(), 0.9);
}

// A vertex of B placed exactly on the line through a segment of A along the first direction
// makes that direction degenerate; the next one answers with the same number.
TEST(CrossingLinkingTest, DegenerateDirectionIsSkipped) {
  const Chain a = TorusLinkComponent(2, 0, 40);
  Chain b = TorusLinkComponent(2, 1, 40);
  const LinkingResult first = CrossingLinkingNumber(a, b);
  ASSERT_EQ(first.status, LinkingStatus::kCertified);
  const Eigen::Vector3d d = first.projection;
  // Move b's vertex 5 onto the line through a's vertex 3 along d (in floating point; the side
  // test of that vertex against a's segments through vertex 3 is then within its bound).
  const double t = (b.col(5) - a.col(3)).dot(d) / d.squaredNorm();
  b.col(5) = a.col(3) + t * d;
  const LinkingResult r = CrossingLinkingNumber(a, b);
  const LinkingResult g = LinkingNumber(a, b);
  ASSERT_EQ(g.status, LinkingStatus::kCertified);
  ASSERT_EQ(r.status, LinkingStatus::kCertified);
  EXPECT_NE(r.projection, d);
  EXPECT_EQ(r.linking_number, g.linking_number);
}

TEST(CrossingLinkingTest, TouchingCurvesAreNotCertifiedAndAutoFallsBack) {
  const Chain a = HopfA(48);
  const LinkingResult r = CrossingLinkingNumber(a, a);
  EXPECT_EQ(r.status, LinkingStatus::kUncertain);
  EXPECT_EQ(r.projection, Eigen::Vector3d::Zero());
  const LinkingResult automatic = LinkingNumberAuto(a, a, LinkingMethod::kAuto);
  EXPECT_EQ(automatic.method, LinkingMethod::kGauss);
  EXPECT_EQ(automatic.status, LinkingStatus::kTouching);
  // Two squares that meet at a corner: every projection sees the shared vertex.
  const Chain sq1 =
      ClosedCurve([](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), 0); }, 4);
  Chain sq2 = sq1;
  sq2.row(0).array() += 2.0;  // shares the vertex (1, 0, 0)
  EXPECT_NE(CrossingLinkingNumber(sq1, sq2).status, LinkingStatus::kCertified);
}

TEST(CrossingLinkingTest, AutoUsesCrossingsAndHonoursTheMethod) {
  const Chain a = TorusLinkComponent(2, 0, 200), b = TorusLinkComponent(2, 1, 200);
  EXPECT_EQ(LinkingNumberAuto(a, b, LinkingMethod::kAuto).method, LinkingMethod::kCrossings);
  const LinkingResult g = LinkingNumberAuto(a, b, LinkingMethod::kGauss);
  EXPECT_EQ(g.method, LinkingMethod::kGauss);
  EXPECT_FALSE(std::isnan(g.gauss_integral));
  WritheStreamOptions far;
  far.far_field_tol = 0.05;
  EXPECT_EQ(LinkingNumberAuto(a, b, LinkingMethod::kAuto, far).method, LinkingMethod::kGauss);
  EXPECT_EQ(LinkingNumberAuto(a, b, LinkingMethod::kAuto).linking_number, g.linking_number);
}

TEST(CrossingLinkingTest, LongCurvesAnswer) {
  const int n = 100000 - 1;  // the most points a chain may have
  const LinkingResult r =
      CrossingLinkingNumber(TorusLinkComponent(7, 0, n), TorusLinkComponent(7, 1, n));
  ASSERT_EQ(r.status, LinkingStatus::kCertified);
  EXPECT_EQ(std::abs(r.linking_number), 7);
  EXPECT_EQ(r.segments_a, n);
}

TEST(CrossingLinkingTest, BadInputIsRefused) {
  const Chain closed = HopfA(16);
  Chain open = HopfB(16);
  open.col(open.cols() - 1) += Eigen::Vector3d(0.1, 0, 0);
  EXPECT_THROW(CrossingLinkingNumber(closed, open), std::invalid_argument);
  Chain nan = HopfB(16);
  nan(1, 3) = std::nan("");
  EXPECT_THROW(CrossingLinkingNumber(closed, nan), std::invalid_argument);
  EXPECT_THROW(CrossingLinkingNumber(Chain(3, 1), closed), std::invalid_argument);
}

}  // namespace
}  // namespace topology
