// The linking number of two closed polygons counted from the signed crossings of a projection,
// exactly, in near-linear time; and the one entry point that picks a method (crossings, then the
// Gauss integral of topology/writhe_stream.h when no projection is generic).
//
// Seen along a direction d, segment a_i a_{i+1} of A and b_j b_{j+1} of B cross when their shadows
// cross; the crossing's sign is
//   ε_ij = sign( (a_{i+1} − a_i) × (b_{j+1} − b_j) · (a_i − b_j) ),
// the same for every d (the over/under order times the handedness of the two shadows), and
//   Lk(A, B) = ½ Σ_{crossing pairs} ε_ij
// (Rolfsen, "Knots and Links", 1976, §5.D; the sign is that of the Gauss integral T of
// writhe_stream.h). Every decision is a sign of a determinant of the input points (and d):
//   shadows cross  ⇔  sign det[a_{i+1} − a_i; d; b_j − a_i] ≠ sign det[a_{i+1} − a_i; d; b_{j+1} −
//   a_i]
//                     and the same with A and B exchanged,
//   ε_ij           =  sign det[a_i − b_j; a_{i+1} − b_j; b_{j+1} − b_j],
// each certified by a static forward error bound in the manner of Shewchuk ("Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", DCG 18, 1997): |det| >
// 10u·permanent (side tests) and (7 + 56u)u·permanent (ε), u = 2⁻⁵³. A direction is degenerate
// when some decision is within its bound (a vertex's shadow on the other curve's shadow, parallel
// overlapping shadows); the next of three fixed generic directions is tried. A crossing whose ε
// is within its bound (two segments that nearly meet) fails every direction: the result is then
// not certified by this method and LinkingNumberAuto falls back to the Gauss integral. Candidate
// pairs come from a uniform grid over B's shadow: O(N_A + N_B + pairs whose shadow boxes overlap)
// time, O(N_A + N_B) memory.
#pragma once

#include "topology/polyline.h"
#include "topology/writhe_stream.h"

namespace topology {

// Lk(A, B) by signed crossings. Fills linking_number, crossings (Σ|ε_ij| in the projection used),
// projection (the direction d used), segments_a/b, method = kCrossings; gauss_integral is NaN,
// error_bound and distance 0. status: kCertified, or kUncertain when no axis is generic
// (projection zero). Chains as LinkingNumber (closed, snapped on a copy); throws
// std::invalid_argument likewise.
LinkingResult CrossingLinkingNumber(const Chain& a, const Chain& b);

// method kCrossings: CrossingLinkingNumber. kGauss: LinkingNumber(a, b, stream). kAuto (the
// default): crossings, and LinkingNumber when they are not certified (stream.far_field_tol > 0
// means the far field was asked for: kAuto then is kGauss).
LinkingResult LinkingNumberAuto(const Chain& a, const Chain& b, LinkingMethod method,
                                const WritheStreamOptions& stream = {});

}  // namespace topology
