// Writhe matrix of two chains: the Gauss linking integral restricted to segment pairs, in closed
// form, with analytic derivatives with respect to every chain point.
//
//   W[i][j] = 1/(4π) ∫_{a ∈ A_i} ∫_{b ∈ B_j} ((a − b) · (da × db)) / |a − b|³
//
// A_i is segment i of chain A (points a_i → a_{i+1}), B_j segment j of chain B. W is
// (N_A − 1) × (N_B − 1): rows are segments of the first chain. For two closed polygons the sum of
// all entries is the Gauss linking number (an integer); for a k-turn helix around a long straight
// pole it is ≈ k. Each entry lies in (−1/2, 1/2).
//
// Closed form: W[i][j] = Ω/(4π), where Ω is the signed area of the spherical quadrilateral that
// the unit vectors (b − a)/|b − a| sweep (Klenin & Langowski 2000), evaluated as two spherical
// triangles with the Van Oosterom–Strackee formula tan(Ω_t/2) = v1·(v2×v3) / (1 + v1·v2 + v2·v3 +
// v3·v1), combined into one atan2. The result is smooth except where the segments intersect.
//
// Degenerate pairs (zero-length segment, touching endpoints, coplanar crossing, collinear overlap)
// give 0 and a zero gradient, never NaN or Inf; near-singular gradients are floored.
//
// Evaluation: 4 segment pairs per step (AVX2 when the CPU has it, else SSE2), blocked in tiles of
// 256 segments of B that stay in L1 (topology/internal/writhe_tile.h); same formula as the scalar
// kernel (entries agree to a few ulp), which remains for B with fewer than 4 segments and for
// matrices of fewer than 4096 pairs (the planners' features: their results stay bit-identical).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "topology/polyline.h"

namespace topology {

enum class WritheVariant {
  kSigned,              // Ω/(4π): signed and normalised (default; sums to the linking number).
  kUnsignedSolidAngle,  // |Ω| in [0, 2π): the unsigned Ω* of the thesis' own code (no 1/(4π)).
};

struct WritheOptions {
  WritheVariant variant = WritheVariant::kSigned;
  // Segment lengths and endpoint distances below this (in the chains' length unit) make a pair
  // degenerate (value 0, gradient 0).
  double degenerate_length = 1e-12;
};

// Derivatives of one entry w = W[i][j] with respect to its four endpoints (world frame, 1/length).
struct SegmentPairGradient {
  Eigen::Vector3d d_a0, d_a1, d_b0, d_b1;
};

// One entry: segment a0→a1 against segment b0→b1. If `grad` is not null it receives ∂w/∂endpoints.
double SegmentPairWrithe(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                         const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                         const WritheOptions& options = {}, SegmentPairGradient* grad = nullptr);

// Sparse Jacobian of a writhe matrix. Entry (i, j) depends only on a_i, a_{i+1}, b_j, b_{j+1}, so
// it is stored as 12 numbers per entry instead of a dense (rows·cols) × 3(N_A + N_B) tensor:
// column k = i·cols + j of `pair` holds [∂W_ij/∂a_i; ∂W_ij/∂a_{i+1}; ∂W_ij/∂b_j; ∂W_ij/∂b_{j+1}].
struct WritheJacobian {
  int rows = 0;  // N_A − 1
  int cols = 0;  // N_B − 1
  Eigen::Matrix<double, 12, Eigen::Dynamic> pair;
};

// Reusable buffers so that repeated evaluations (one per solver step) do not allocate once sized.
struct WritheWorkspace {
  std::vector<Eigen::Vector3d> dir_row0, dir_row1;  // unit vectors b_q − a_p for two rows of p
  std::vector<double> len_row0, len_row1;           // and their lengths
  std::vector<double> x_row, y_row, w_row;          // per-pair atan2 arguments and results
  std::vector<char> b_degenerate;                   // per segment of B: shorter than the floor
  std::vector<double> simd_b, simd_scratch;         // SIMD kernel: B as arrays, direction tiles
  std::vector<std::uint8_t> a_degenerate;           // per segment of A: shorter than the floor
};

// W = writhe matrix of A (3×N_A) against B (3×N_B); W is resized to (N_A−1)×(N_B−1).
// Throws std::invalid_argument if a chain has fewer than 2 points, a non-finite coordinate or one
// beyond ±kMaxCoordinate (1e100). Cost O(N_A·N_B); allocation-free when W and `ws` already have
// the right sizes.
void WritheMatrix(const Chain& a, const Chain& b, const WritheOptions& options, Eigen::MatrixXd* w,
                  WritheWorkspace* ws);
Eigen::MatrixXd WritheMatrix(const Chain& a, const Chain& b, const WritheOptions& options = {});

// W and its sparse Jacobian (see WritheJacobian) in one pass.
void WritheMatrixWithJacobian(const Chain& a, const Chain& b, const WritheOptions& options,
                              Eigen::MatrixXd* w, WritheJacobian* jac, WritheWorkspace* ws);

// Σ_ij W[i][j] (streamed on one thread, never forming W; see topology/writhe_stream.h for
// threads, row sums and an error bound). For closed A and B: the Gauss linking number.
double TotalWrithe(const Chain& a, const Chain& b, const WritheOptions& options = {});

// Self-writhe of one chain: Σ_{i≠j} W[i][j] over its own segments = 2 Σ_{i<j−1} W[i][j]
// (adjacent pairs contribute 0).
double SelfWrithe(const Chain& a, const WritheOptions& options = {});

// Gradient of Σ_ij c_ij W_ij with respect to the points: grad_a is 3×N_A, grad_b is 3×N_B.
// `weights` is rows×cols; pass an empty matrix for all-ones (the gradient of the total).
void WeightedWritheGradient(const WritheJacobian& jac, const Eigen::MatrixXd& weights,
                            Eigen::Matrix3Xd* grad_a, Eigen::Matrix3Xd* grad_b);

// Chain rule to any parameters q: d vec(W)/dq = ∂W/∂A · dA/dq + ∂W/∂B · dB/dq.
//   da_dq: (3·N_A)×n_q, rows 3p..3p+2 = ∂a_p/∂q (a point Jacobian); may be empty (A static).
//   db_dq: (3·N_B)×n_q likewise; may be empty (B static).
//   out:   (rows·cols)×n_q, row i·cols + j (row-major vec(W)), resized if needed.
// Cost O(rows·cols·n_q); no (rows·cols)×3N intermediate is formed.
void ChainWritheJacobian(const WritheJacobian& jac, const Eigen::MatrixXd& da_dq,
                         const Eigen::MatrixXd& db_dq, Eigen::MatrixXd* out);

}  // namespace topology
