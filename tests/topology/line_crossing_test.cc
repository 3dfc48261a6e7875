#include "topology/line_crossing.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "topology/winding.h"

namespace topology {
namespace {

const Eigen::Vector3d kA(0, 0, 0), kB(0, 0, 2);  // the line: the z axis, t = z / 2

// A 3-point chain (two segments along y, at height z) translated along x: x(s) = −0.3 + s, so
// its first segment, y ∈ [−0.5, 0.5], meets the z axis at s = 0.3, and its second, y ∈ [0.5, 1.5],
// only by its extension.
ChainMotion Sweep(double z) {
  return [z](double s, Chain* p) {
    p->resize(3, 3);
    const double x = -0.3 + s;
    p->col(0) << x, -0.5, z;
    p->col(1) << x, 0.5, z;
    p->col(2) << x, 1.5, z;
  };
}

TEST(LineCrossing, LocatesTheSegmentTheMomentAndThePointOnTheLine) {
  for (double z : {0.5, 5.0, -1.0}) {
    const auto crossings = LocateLineCrossings(Sweep(z), kA, kB);
    ASSERT_EQ(crossings.size(), 1u) << "z = " << z;
    EXPECT_EQ(crossings[0].segment, 0);
    EXPECT_NEAR(crossings[0].s, 0.3, 1e-9);
    EXPECT_NEAR(crossings[0].line_param, z / 2.0, 1e-9);  // inside [0, 1] only for z = 0.5
  }
}

TEST(LineCrossing, TheCrossingIsWhereTheWindingJumpsByATurn) {
  const Axis axis{kA, kB - kA};
  const auto crossings = LocateLineCrossings(Sweep(0.5), kA, kB);
  ASSERT_EQ(crossings.size(), 1u);
  const double s = crossings[0].s;
  Chain before, after;
  Sweep(0.5)(s - 1e-6, &before);
  Sweep(0.5)(s + 1e-6, &after);
  EXPECT_NEAR(std::abs(WindingNumber(after, axis) - WindingNumber(before, axis)), 1.0, 1e-4);
  // Away from the crossing the winding changes continuously.
  Chain early, later;
  Sweep(0.5)(0.1, &early);
  Sweep(0.5)(0.1 + 2e-6, &later);
  EXPECT_LT(std::abs(WindingNumber(later, axis) - WindingNumber(early, axis)), 1e-4);
}

TEST(LineCrossing, NoPassNoCrossing) {
  // Moving along the line's direction, or staying on one side of it.
  const ChainMotion along = [](double s, Chain* p) {
    p->resize(3, 2);
    p->col(0) << 0.2, -0.5, s;
    p->col(1) << 0.2, 0.5, s;
  };
  EXPECT_TRUE(LocateLineCrossings(along, kA, kB).empty());
  // A 0.3 m segment turning about its end 0.5 m from the line sweeps a disc that misses the line
  // by 0.2 m. At s = 0 it points away from the line along the same ray, so f = 0 there: a zero
  // at an end that is no pass.
  const ChainMotion turn = [](double s, Chain* p) {
    p->resize(3, 2);
    p->col(0) << 0.5, 0, 1;
    p->col(1) << 0.5 + 0.3 * std::cos(3 * s), 0.3 * std::sin(3 * s), 1;
  };
  EXPECT_TRUE(LocateLineCrossings(turn, kA, kB).empty());
}

TEST(LineCrossing, TwoSegmentsPassingAtDifferentMomentsAreSortedByS) {
  // Two unit arms turning about their pivots: the first about (0.5, 0) at z = 1.5 by
  // φ = π/2 + 0.7π s (it points at the line when φ = π: s = 5/7), the second about (0, 0.6) at
  // z = 0.25 by φ = 1.4π + 0.4π s (pointing at the line when φ = 3π/2: s = 1/4). The segment
  // between them never has the line between its ends.
  const ChainMotion motion = [](double s, Chain* p) {
    const double a = M_PI / 2 + 0.7 * M_PI * s, b = 1.4 * M_PI + 0.4 * M_PI * s;
    p->resize(3, 4);
    p->col(0) << 0.5, 0, 1.5;
    p->col(1) << 0.5 + std::cos(a), std::sin(a), 1.5;
    p->col(2) << 0, 0.6, 0.25;
    p->col(3) << std::cos(b), 0.6 + std::sin(b), 0.25;
  };
  const auto c = LocateLineCrossings(motion, kA, kB);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].segment, 2);
  EXPECT_NEAR(c[0].s, 0.25, 1e-9);
  EXPECT_NEAR(c[0].line_param, 0.125, 1e-9);
  EXPECT_EQ(c[1].segment, 0);
  EXPECT_NEAR(c[1].s, 5.0 / 7.0, 1e-9);
  EXPECT_NEAR(c[1].line_param, 0.75, 1e-9);
}

TEST(LineCrossing, ALineAnywhereIsMeasuredFromItsFirstPoint) {
  // The z-axis case moved and turned: the line through a = (1, 2, 3) along a unit direction d, a
  // segment perpendicular to d through the point a + 0.7 (b − a) at s = 0.4, swept along n.
  const Eigen::Vector3d a(1, 2, 3), d = Eigen::Vector3d(1, -2, 2) / 3.0, b = a + 1.5 * d;
  const Eigen::Vector3d n = d.unitOrthogonal(), m = d.cross(n);
  const Eigen::Vector3d centre = a + 0.7 * (b - a);
  const ChainMotion motion = [&](double s, Chain* p) {
    p->resize(3, 2);
    p->col(0) = centre + (s - 0.4) * n - 0.5 * m;
    p->col(1) = centre + (s - 0.4) * n + 0.5 * m;
  };
  const auto c = LocateLineCrossings(motion, a, b);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].s, 0.4, 1e-9);
  EXPECT_NEAR(c[0].line_param, 0.7, 1e-9);
}

TEST(LineCrossing, RejectsADegenerateLineAndAChainThatChangesSize) {
  EXPECT_THROW(LocateLineCrossings(Sweep(0.5), kA, kA), std::invalid_argument);
  const ChainMotion grows = [](double s, Chain* p) {
    p->resize(3, s < 0.5 ? 2 : 3);
    p->setOnes();
  };
  EXPECT_THROW(LocateLineCrossings(grows, kA, kB), std::invalid_argument);
  const ChainMotion nan_inside = [](double s, Chain* p) {
    Sweep(0.5)(s, p);
    if (s > 0.0 && s < 1.0) (*p)(0, 1) = std::nan("");
  };
  EXPECT_THROW(LocateLineCrossings(nan_inside, kA, kB), std::invalid_argument);
  for (double tolerance : {0.0, 1.0, std::nan("")}) {
    EXPECT_THROW(LocateLineCrossings(Sweep(0.5), kA, kB, tolerance), std::invalid_argument);
  }
}

// LineDistanceBeyondEnds on hand-computed chains about the z axis from kA to kB (t = z here).
TEST(LineDistanceBeyondEnds, HandComputedChains) {
  Chain p(3, 2);
  p << 0.3, 0.3, 0, 0, 2.5, 3.5;  // parallel to the line at 0.3 m, above its end (z = 2)
  EXPECT_NEAR(LineDistanceBeyondEnds(p, kA, kB), 0.3, 1e-12);
  p << -1, 1, 0.2, 0.2, 3, 3;  // across above the end at z = 3: closest at x = 0, 0.2 m
  EXPECT_NEAR(LineDistanceBeyondEnds(p, kA, kB), 0.2, 1e-12);
  p << -1, 1, 0, 0, -0.5, -0.5;  // through the line below the start
  EXPECT_NEAR(LineDistanceBeyondEnds(p, kA, kB), 0.0, 1e-12);
  p << -1, 1, 0, 0, 1, 1;  // through the line between the ends: not beyond
  EXPECT_EQ(LineDistanceBeyondEnds(p, kA, kB), std::numeric_limits<double>::infinity());
  // Through the line between the ends on a slant that leaves above the end at z = 2: the part with
  // z > 2 is x ∈ [1, 2], nearest the line at x = 1, 1 m away.
  p << 0, 2, 0, 0, 1, 3;
  EXPECT_NEAR(LineDistanceBeyondEnds(p, kA, kB), 1.0, 1e-12);
  // The same line given the other way round (b to a): the same distances.
  EXPECT_NEAR(LineDistanceBeyondEnds(p, kB, kA), 1.0, 1e-12);
  EXPECT_THROW(LineDistanceBeyondEnds(p, kA, kA), std::invalid_argument);
  EXPECT_THROW(LineDistanceBeyondEnds(Chain(3, 1), kA, kB), std::invalid_argument);
}

// The closed form against the minimum over 20,001 points per segment of random chains about a
// random line (beyond the ends only).
TEST(LineDistanceBeyondEnds, AgreesWithDenseSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    Chain p(3, 6);
    for (int i = 0; i < p.cols(); ++i) p.col(i) = 1.5 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double length = (b - a).norm();
    const Eigen::Vector3d d = (b - a) / length;
    double sampled = std::numeric_limits<double>::infinity();
    for (int j = 0; j + 1 < p.cols(); ++j) {
      for (int k = 0; k <= 20000; ++k) {
        const Eigen::Vector3d x = p.col(j) + (k / 20000.0) * (p.col(j + 1) - p.col(j));
        const double t = d.dot(x - a);
        if (t >= 0.0 && t <= length) continue;
        sampled = std::min(sampled, (x - a - t * d).norm());
      }
    }
    const double exact = LineDistanceBeyondEnds(p, a, b);
    if (std::isinf(sampled)) {  // no sample beyond the ends (the chain is within the slab)
      EXPECT_TRUE(std::isinf(exact)) << "trial " << trial;
      continue;
    }
    ASSERT_LE(exact, sampled + 1e-12) << "trial " << trial;  // a minimum, never above a sample
    EXPECT_NEAR(exact, sampled, 1e-3) << "trial " << trial;
  }
}

}  // namespace
}  // namespace topology
