// Barnes–Hut evaluation of the Gauss linking integral of two long chains with a rigorous bound on
// the approximation error (Qu & James, "Fast linking numbers for topology verification of loopy
// structures", ACM Trans. Graph. 40(4), SIGGRAPH 2021).
//
//   T = 1/(4π) ∫_A ∫_B ((a − b) · (da × db)) / |a − b|³       (= Σ_ij W[i][j], topology/writhe.h)
//
// Each chain's segments are split into a binary tree of contiguous index ranges. For a node with
// centre c, put α = a − c; its moments are T = ∫ da, M_k = ∫ α_k da, Q_kl = ∫ α_k α_l da (exact
// for straight segments), its length L = ∫|da| and radius r ≥ max |α|. A pair of nodes (A-node,
// B-node) with centres at distance d and s = r_A + r_B < d is "far": the kernel K(r) = r/|r|³ is
// expanded to second order about r₀ = c_A − c_B, which makes its contribution a function of the
// moments only. The Taylor remainder of K·w (|w| = 1) is (1/6) D⁴(1/|r|)[δ, δ, δ, w] with
// |δ| ≤ s, and |D⁴(1/|r|)| ≤ 4!/|r|⁵ (Legendre bound, symmetric forms), so the pair's error is
//   e ≤ L_A L_B s³ / (π (d − s)⁵).
// A far pair is used when e ≤ tol · L_A L_B / (L_A,total · L_B,total); the accepted pairs
// partition A × B, so the approximation errors add to at most tol. Other pairs are split (the
// node with the larger radius) down to leaves, whose segment pairs take the exact SIMD kernel.
#pragma once

#include <functional>

#include "topology/polyline.h"
#include "topology/writhe.h"

namespace topology {

struct FarFieldOptions {
  // Bound on |T_far − T_exact| from the approximation (T is a pure number); must be > 0.
  double tol = 1e-2;
  int leaf_segments = 32;  // segments per leaf of the trees (rounded up to a multiple of 4)
  int threads = 0;         // 0: std::thread::hardware_concurrency(); results do not depend on it
  double degenerate_length = 1e-12;  // as WritheOptions
  // As WritheStreamOptions::progress: (segment pairs covered, N_A−1 · N_B−1) on the calling
  // thread after each unit of work; it may throw to stop.
  std::function<void(long long, long long)> progress;
};

struct FarFieldSums {
  int rows = 0, cols = 0;            // N_A − 1, N_B − 1
  double total = 0.0;                // T_far
  double approximation_bound = 0.0;  // Σ e over the far pairs used (≤ tol)
  double rounding_bound = 0.0;       // floating-point error of the exact and far parts
  double error_bound = 0.0;          // approximation_bound + rounding_bound ≥ |T_far − T|
  long long exact_pairs = 0;         // segment pairs evaluated exactly
  long long far_node_pairs = 0;      // node pairs replaced by their expansion
  long long degenerate_pairs = 0;    // exact pairs reported as 0 (touching, zero length)
};

// T of A (3×N_A) and B (3×N_B), signed variant. Throws std::invalid_argument as WritheMatrix for a
// bad chain or for tol ≤ 0 / not finite. Deterministic for any thread count. Memory O(N_A + N_B).
FarFieldSums FarFieldGaussIntegral(const Chain& a, const Chain& b,
                                   const FarFieldOptions& options = {});

}  // namespace topology
