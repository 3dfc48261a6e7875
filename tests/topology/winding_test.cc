#include "topology/winding.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "tests/topology/test_chains.h"

namespace topology {
namespace {

const Axis kZ{{0, 0, 0}, {0, 0, 1}};

TEST(WindingTest, ClosedLoopsAreIntegers) {
  const Chain circle = testing::HopfA(40);  // counter-clockwise about +z
  EXPECT_NEAR(WindingNumber(circle, kZ), 1.0, 1e-12);
  EXPECT_NEAR(WindingNumber(circle.rowwise().reverse(), kZ), -1.0, 1e-12);
  EXPECT_NEAR(WindingNumber(circle, Axis{{0, 0, 0}, {0, 0, -2}}), -1.0, 1e-12);
  Chain away = circle;
  away.row(0).array() += 5.0;  // axis outside the loop
  EXPECT_NEAR(WindingNumber(away, kZ), 0.0, 1e-12);
  // Three times around, and a planar loop around an off-centre point inside it.
  EXPECT_NEAR(WindingNumber(testing::Helix(3, 1.0, 0.0, 90), kZ), 3.0, 1e-12);
  EXPECT_NEAR(PlanarWinding(circle, {0.3, -0.2, 0}, {0, 0, 1}), 1.0, 1e-12);
}

TEST(WindingTest, HelixAboutPoleCountsFractionalTurns) {
  for (double turns : {0.25, 1.5, 2.75}) {
    EXPECT_NEAR(WindingNumber(testing::Helix(turns, 0.3, 1.0, 100), kZ), turns, 1e-12);
  }
}

TEST(WindingTest, UnsignedEq4CountsBackAndForthTwice) {
  // Angles +1, −0.5, +1, −0.5, +1 rad about the centre: signed 2/2π, unsigned 4/2π.
  const double angles[] = {0, 1, 0.5, 1.5, 1.0, 2.0};
  Chain c(3, 6);
  for (int i = 0; i < 6; ++i) c.col(i) << std::cos(angles[i]), std::sin(angles[i]), 0;
  EXPECT_NEAR(WindingNumber(c, kZ), 2.0 / (2 * M_PI), 1e-12);
  WindingOptions o;
  o.variant = WindingVariant::kUnsignedArccos;
  EXPECT_NEAR(WindingNumber(c, kZ, o), 4.0 / (2 * M_PI), 1e-12);
}

TEST(WindingTest, GradientsMatchFiniteDifferences) {
  std::mt19937 rng(3);
  const Chain chain = testing::RandomChain(8, 0.5, {1.0, 0.5, 0.2}, &rng);
  const Axis axis{{0.1, -0.2, 0.0}, {0.2, 0.3, 1.0}};
  for (WindingVariant v : {WindingVariant::kSigned, WindingVariant::kUnsignedArccos}) {
    WindingOptions o;
    o.variant = v;
    Eigen::Matrix3Xd grad;
    Eigen::MatrixXd seg_jac;
    WindingNumber(chain, axis, o, &grad);
    const Eigen::VectorXd seg = SegmentWindings(chain, axis, o, &seg_jac);
    EXPECT_NEAR(seg.sum(), WindingNumber(chain, axis, o), 1e-12);
    const double h = 1e-6;
    for (int p = 0; p < chain.cols(); ++p) {
      for (int c = 0; c < 3; ++c) {
        Chain plus = chain, minus = chain;
        plus(c, p) += h;
        minus(c, p) -= h;
        const double fd = (WindingNumber(plus, axis, o) - WindingNumber(minus, axis, o)) / (2 * h);
        EXPECT_NEAR(grad(c, p), fd, 1e-7) << "point " << p << " coord " << c;
        const Eigen::VectorXd fd_seg =
            (SegmentWindings(plus, axis, o) - SegmentWindings(minus, axis, o)) / (2 * h);
        EXPECT_LT((seg_jac.col(3 * p + c) - fd_seg).cwiseAbs().maxCoeff(), 1e-7);
      }
    }
  }
}

TEST(WindingTest, SignedInteriorGradientCancels) {
  const Chain h = testing::Helix(1.5, 0.4, 0.5, 30);
  Eigen::Matrix3Xd grad;
  WindingNumber(h, kZ, {}, &grad);
  EXPECT_LT(grad.middleCols(1, h.cols() - 2).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(grad.col(0).norm(), 0.1);
}

TEST(WindingTest, PointsOnTheAxisAreFiniteAndBadInputThrows) {
  Chain c(3, 3);
  c << 0, 1, 0,  //
      0, 0, 1,   //
      0, 0, 0;
  Eigen::Matrix3Xd grad;
  const double w = WindingNumber(c, kZ, {}, &grad);
  EXPECT_TRUE(std::isfinite(w));
  EXPECT_TRUE(grad.allFinite());
  EXPECT_THROW(WindingNumber(c, Axis{{0, 0, 0}, {0, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(WindingNumber(c.leftCols(1), kZ), std::invalid_argument);
  // Scale-invariant up to the coordinate limit, refused beyond it.
  EXPECT_NEAR(WindingNumber(1e99 * c, kZ), w, 1e-12);
  EXPECT_THROW(WindingNumber(1e155 * c, kZ), std::invalid_argument);
  EXPECT_THROW(WindingNumber(c, Axis{{1e155, 0, 0}, {0, 0, 1}}), std::invalid_argument);
}

}  // namespace
}  // namespace topology
