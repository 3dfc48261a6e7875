// Where a moving chain passes through a line: the events that make its winding number about the
// line jump by a whole turn, located on the line so that a caller can tell a pass through an
// object on the line (a pole) from a pass round the object's end.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "topology/polyline.h"

namespace topology {

// One pass of chain segment [p_j, p_{j+1}] through the line a + t (b − a).
struct LineCrossing {
  int segment = -1;         // j
  double s = 0.0;           // the motion parameter at the pass, in [0, 1]
  double line_param = 0.0;  // t of the point where the segment meets the line (0 at a, 1 at b)
};

// The chain at motion parameter s ∈ [0, 1]: fills `points` (3 × N, the same N for every s).
using ChainMotion = std::function<void(double s, Chain* points)>;

// The passes of a chain moving along `motion` (s from 0 to 1) through the line through `a` and
// `b` (a ≠ b). With d̂ = (b − a)/|b − a| and u_i(s) the projection of p_i(s) − a onto the plane
// ⟂ d̂, segment j's signed winding angle atan2(d̂·(u_j × u_{j+1}), u_j·u_{j+1}) jumps by 2π exactly
// where f_j(s) = d̂·(u_j × u_{j+1}) changes sign with u_j·u_{j+1} < 0 (the line between the
// segment's ends). For every j with sign f_j(0) ≠ sign f_j(1) the root is found by bisection in s
// (to |Δs| ≤ s_tolerance, at most 64 halvings) and kept when u_j·u_{j+1} < 0 there; the meeting
// point is p_j + λ (p_{j+1} − p_j), λ = |u_j| / (|u_j| + |u_{j+1}|), and line_param its
// coordinate along the line. One root of f_j per segment per call: a segment passing twice within
// [0, 1] (no sign change) is not seen, and when f_j also has a root where only the segment's
// extension meets the line, bisection may settle there and the pass is dropped (the caller then
// sees a winding jump with no located pass); callers take steps small enough for one root per
// segment. A root exactly at s = 0 or 1 is found at that end. Result sorted by s. Throws
// std::invalid_argument when a = b, a point is not finite, N changes with s, or s_tolerance is
// not in (0, 1).
std::vector<LineCrossing> LocateLineCrossings(const ChainMotion& motion, const Eigen::Vector3d& a,
                                              const Eigen::Vector3d& b, double s_tolerance = 1e-10);

// The smallest distance from chain `p` (3 × N, N ≥ 2) to the line through `a` and `b`, over the
// chain's points beyond the segment [a, b] along the line: points whose coordinate
// t = d̂·(x − a), d̂ = (b − a)/|b − a|, is < 0 or > |b − a|. m; +infinity when no point of the
// chain is beyond. Segment j, x(λ) = p_j + λ (p_{j+1} − p_j) with λ ∈ [0, 1], has t(λ) linear and
// its squared distance to the line quadratic in λ, so its minimum over each of the (at most two)
// λ-intervals beyond the ends is the vertex of that quadratic clamped to the interval. A chain
// near the line beyond an object on [a, b] is one small move from passing the line there (a
// winding jump round the object's end). Throws std::invalid_argument when a = b or N < 2.
double LineDistanceBeyondEnds(const Chain& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace topology
