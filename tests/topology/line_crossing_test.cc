#include "topology/line_crossing.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
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

}  // namespace
}  // namespace topology
