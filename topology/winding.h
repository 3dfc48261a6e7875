// Winding numbers of a chain about an axis, and of a planar chain about a point.
#pragma once

#include <Eigen/Core>

#include "topology/polyline.h"

namespace topology {

enum class WindingVariant {
  kSigned,  // (1/2π) Σ_i atan2(n̂·(u_i × u_{i+1}), u_i·u_{i+1}) (default): continuous in
            // the points while the chain does not cross the axis; integer for closed loops.
  kUnsignedArccos,  // (1/2π) Σ_i arccos(û_i·û_{i+1}): Eq. 4 of Ivan et al., IJRR 2013. Counts
                    // back-and-forth motion twice; kept for faithfulness to the paper.
};

// Oriented axis: the line through `point` along `direction` (need not be unit length, must be
// non-zero). Angles are measured counter-clockwise about the direction (right-hand rule).
struct Axis {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};

struct WindingOptions {
  WindingVariant variant = WindingVariant::kSigned;
  // Points closer than this to the axis contribute 0 (the angle is undefined there), and
  // 1/|u|² in the gradient is floored at 1/distance_floor².
  double distance_floor = 1e-9;
};

// Winding number of `chain` (3×N, N ≥ 2) about `axis`:
//   u_i = P (p_i − axis.point), P = I − d̂d̂ᵀ (projection onto the plane ⟂ d̂),
//   w = (1/2π) Σ_{i=0}^{N−2} Δθ_i, with Δθ_i the variant's angle between u_i and u_{i+1}.
// If `grad` is not null it is resized to 3×N and receives ∂w/∂p_i. For the signed variant
// ∂Δθ_i/∂p_{i+1} = (d̂ × u_{i+1})/|u_{i+1}|² and ∂Δθ_i/∂p_i = −(d̂ × u_i)/|u_i|², so interior
// terms cancel and only the two end points carry gradient.
// Throws std::invalid_argument for fewer than 2 points, non-finite input, a coordinate beyond
// ±kMaxCoordinate (1e100) or a zero direction.
double WindingNumber(const Chain& chain, const Axis& axis, const WindingOptions& options = {},
                     Eigen::Matrix3Xd* grad = nullptr);

// Per-segment contributions Δθ_i/(2π) (size N−1); their sum is WindingNumber. If `jac` is not
// null it is resized to (N−1)×3N with row i = ∂(Δθ_i/2π)/∂(p_0..p_{N−1}) (point k at columns
// 3k..3k+2).
Eigen::VectorXd SegmentWindings(const Chain& chain, const Axis& axis,
                                const WindingOptions& options = {}, Eigen::MatrixXd* jac = nullptr);

// A planar chain about a point: the same as WindingNumber about the axis through `center` along
// the plane normal `normal` (points are projected onto the plane).
double PlanarWinding(const Chain& chain, const Eigen::Vector3d& center,
                     const Eigen::Vector3d& normal, const WindingOptions& options = {},
                     Eigen::Matrix3Xd* grad = nullptr);

}  // namespace topology
