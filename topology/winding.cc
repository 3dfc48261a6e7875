#include "topology/winding.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace topology {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
using Eigen::Vector3d;

void Check(const Chain& chain, const Axis& axis) {
  if (chain.cols() < 2) {
    throw std::invalid_argument("winding: chain needs at least 2 points, got " +
                                std::to_string(chain.cols()));
  }
  if (!chain.allFinite()) throw std::invalid_argument("winding: chain has a non-finite coordinate");
  if (!axis.point.allFinite() || !axis.direction.allFinite() || axis.direction.norm() == 0.0) {
    throw std::invalid_argument("winding: axis direction must be finite and non-zero");
  }
  if (chain.cwiseAbs().maxCoeff() > kMaxCoordinate ||
      axis.point.cwiseAbs().maxCoeff() > kMaxCoordinate ||
      axis.direction.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    throw std::invalid_argument(
        "winding: a coordinate is beyond ±1e100 (squared lengths would overflow)");
  }
}

// Δθ of segment i and its derivatives with respect to p_i (g0) and p_{i+1} (g1).
double SegmentAngle(const Vector3d& u0, const Vector3d& u1, const Vector3d& d,
                    const WindingOptions& opt, Vector3d* g0, Vector3d* g1) {
  const double n0 = u0.squaredNorm(), n1 = u1.squaredNorm();
  const double floor2 = opt.distance_floor * opt.distance_floor;
  if (n0 < floor2 || n1 < floor2) {
    if (g0) g0->setZero(), g1->setZero();
    return 0.0;
  }
  if (opt.variant == WindingVariant::kSigned) {
    const double s = d.dot(u0.cross(u1)), c = u0.dot(u1);
    if (g0) {
      *g0 = -d.cross(u0) / n0;
      *g1 = d.cross(u1) / n1;
    }
    return std::atan2(s, c);
  }
  // Unsigned: arccos of the cosine between the projected vectors.
  const double inv = 1.0 / std::sqrt(n0 * n1);
  const double c = std::clamp(u0.dot(u1) * inv, -1.0, 1.0);
  if (g0) {
    // d arccos(c) = −dc / sqrt(1 − c²), floored; dc/du0 = (u1/|u0||u1|) − c u0/|u0|².
    const double k = -1.0 / std::sqrt(std::max(1.0 - c * c, 1e-12));
    *g0 = k * (u1 * inv - c * u0 / n0);
    *g1 = k * (u0 * inv - c * u1 / n1);
  }
  return std::acos(c);
}

}  // namespace

Eigen::VectorXd SegmentWindings(const Chain& chain, const Axis& axis, const WindingOptions& options,
                                Eigen::MatrixXd* jac) {
  Check(chain, axis);
  const Vector3d d = axis.direction.normalized();
  const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - d * d.transpose();
  const Eigen::Index n = chain.cols();
  Eigen::VectorXd out(n - 1);
  if (jac) jac->setZero(n - 1, 3 * n);
  Vector3d g0, g1;
  Vector3d u0 = proj * (chain.col(0) - axis.point);
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const Vector3d u1 = proj * (chain.col(i + 1) - axis.point);
    out(i) = SegmentAngle(u0, u1, d, options, jac ? &g0 : nullptr, jac ? &g1 : nullptr) / kTwoPi;
    if (jac) {
      // u = P (p − c) and P is symmetric, so ∂/∂p = P ∂/∂u.
      jac->block<1, 3>(i, 3 * i) = (proj * g0).transpose() / kTwoPi;
      jac->block<1, 3>(i, 3 * i + 3) = (proj * g1).transpose() / kTwoPi;
    }
    u0 = u1;
  }
  return out;
}

double WindingNumber(const Chain& chain, const Axis& axis, const WindingOptions& options,
                     Eigen::Matrix3Xd* grad) {
  Check(chain, axis);
  const Vector3d d = axis.direction.normalized();
  const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - d * d.transpose();
  const Eigen::Index n = chain.cols();
  if (grad) grad->setZero(3, n);
  double sum = 0.0;
  Vector3d g0, g1;
  Vector3d u0 = proj * (chain.col(0) - axis.point);
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const Vector3d u1 = proj * (chain.col(i + 1) - axis.point);
    sum += SegmentAngle(u0, u1, d, options, grad ? &g0 : nullptr, grad ? &g1 : nullptr);
    if (grad) {
      grad->col(i) += proj * g0 / kTwoPi;
      grad->col(i + 1) += proj * g1 / kTwoPi;
    }
    u0 = u1;
  }
  return sum / kTwoPi;
}

double PlanarWinding(const Chain& chain, const Eigen::Vector3d& center,
                     const Eigen::Vector3d& normal, const WindingOptions& options,
                     Eigen::Matrix3Xd* grad) {
  return WindingNumber(chain, Axis{center, normal}, options, grad);
}

}  // namespace topology
