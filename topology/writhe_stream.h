// Streaming sums of a writhe matrix: the total, the row sums, block sums and the Gauss linking
// number of two chains for any length in O(N_A + N_B) memory, never materialising the
// (N_A − 1) × (N_B − 1) matrix W of topology/writhe.h (same kernel, same values).
//
//   total      T = Σ_i Σ_j W[i][j]                (Gauss linking integral of A and B)
//   row sums   r_i = Σ_j W[i][j]                  (N_A − 1 values)
//   block sums S[p][q] = Σ_{i ∈ I_p} Σ_{j ∈ J_q} W[i][j]  (row blocks I_p, column blocks J_q)
//
// Summation order is fixed: each row is summed as four interleaved partial sums (j mod 4) added
// at the end, then the row sums in order with Neumaier's compensated sum. A row's value does not
// depend on which thread computed it, so every result is bitwise the same for any thread count.
//
// Error bound (u = 2⁻⁵³, the unit roundoff). For a pair with kernel argument Z = X + iY
// (W[i][j] = −arg Z / 2π, |Z| ≤ 16) the computed entry is within
//   e_ij = u (1024 / |Z| + 16) / (2π)
// of the exact closed form (each triangle's x + iy is computed with absolute error ≤ 128u from
// unit vectors accurate to 4u, |x + iy| ≤ 4; SLEEF's atan2 adds ≤ 3.5 ulp). Pairs whose segments
// nearly touch have a small |Z| and a large e_ij; for |Z| ≥ 1 (almost all pairs) 1/|Z| is
// bounded by 1. The sums add ≤ (cols/4 + 5) u Σ|W[i][j]|, so
//   |T_computed − T_exact| ≤ B = 1.01 (Σ e_ij + (cols/4 + 5) u Σ|W[i][j]|)
// (signed variant; the kernel part ×4π for the unsigned one). docs/methods.md derives it.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <span>

#include "base/enum_names.h"
#include "topology/polyline.h"
#include "topology/writhe.h"

namespace topology {

struct WritheStreamOptions {
  WritheOptions writhe;
  // Worker threads (the calling thread is one of them); 0: std::thread::hardware_concurrency().
  // Inputs under 2·10⁵ segment pairs use one thread. Results do not depend on it.
  int threads = 0;
  bool row_sums = false;  // also return r_i (StreamWritheSums only)
  // > 0: Barnes–Hut far field (topology/gauss_far_field.h) with this bound on the approximation
  // error, added to error_bound; signed variant only, no row sums, abs_total is NaN.
  double far_field_tol = 0.0;
  // Called on the calling thread after each unit of work it finished, with (segment pairs done,
  // segment pairs total). It may throw (e.g. to stop on Ctrl-C): the other threads stop after
  // their current unit and the exception propagates once they have joined.
  std::function<void(long long, long long)> progress;
};

struct WritheSums {
  int rows = 0, cols = 0;    // N_A − 1, N_B − 1
  double total = 0.0;        // T
  double abs_total = 0.0;    // Σ|W[i][j]| (NaN with far_field_tol)
  double error_bound = 0.0;  // B above: |total − exact T| ≤ error_bound
  long long degenerate_pairs =
      0;                     // pairs the kernel reports as 0 (touching, crossing, zero length)
  Eigen::VectorXd row_sums;  // (N_A − 1) r_i when options.row_sums, else empty
};

// T, B and optionally r_i in O(N_A + N_B) memory (per thread: the workspace of one row).
// Throws std::invalid_argument as WritheMatrix for a bad chain. Cost O(N_A·N_B).
WritheSums StreamWritheSums(const Chain& a, const Chain& b,
                            const WritheStreamOptions& options = {});

struct WritheBlockSums {
  // S, (⌈rows/row_block⌉) × (⌈cols/col_block⌉): block p covers segments
  // [p·row_block, min((p+1)·row_block, rows)) of A, block q likewise of B.
  Eigen::MatrixXd sums;
  int row_block = 1, col_block = 1;  // segments per block (the last block may be shorter)
};

// Block sums with at most max_rows × max_cols blocks (≥ 1 each): row_block = ⌈rows/max_rows⌉,
// col_block = ⌈cols/max_cols⌉; with blocks of 1 segment S equals W. O(N_A + N_B + cells) memory.
WritheBlockSums BlockWritheSums(const Chain& a, const Chain& b, int max_rows, int max_cols,
                                const WritheStreamOptions& options = {});

// A chain is closed when it has at least 4 points and its last point repeats its first
// (polyline.h), up to |p_{N−1} − p_0| ≤ kClosedGap · (diagonal of the chain's bounding box), so
// that curves sampled at t = 0 and t = 2π in floating point count as closed.
inline constexpr double kClosedGap = 1e-9;
bool IsClosedChain(const Chain& c);

enum class LinkingStatus {
  kCertified,   // T is within B of exactly one integer: the linking number
  kNotInteger,  // T is further than B from every integer (curves cross, or B was exceeded)
  kTouching,    // some segment pairs touch or cross (degenerate_pairs > 0): not defined
  kUncertain,   // B ≥ 1/2: the bound cannot single out one integer
};
inline constexpr base::EnumName<LinkingStatus> kLinkingStatusNames[] = {
    {LinkingStatus::kCertified, "certified"},
    {LinkingStatus::kNotInteger, "not_integer"},
    {LinkingStatus::kTouching, "touching"},
    {LinkingStatus::kUncertain, "uncertain"}};
constexpr std::span<const base::EnumName<LinkingStatus>> EnumNames(LinkingStatus) {
  return kLinkingStatusNames;
}
inline const char* LinkingStatusName(LinkingStatus s) { return base::ToName(s); }

// How a linking number is computed: signed crossings of a projection (exact, certified by
// error-bounded predicates; topology/linking_crossings.h) or the Gauss integral T (below); kAuto
// tries the crossings and falls back to T.
enum class LinkingMethod { kAuto, kCrossings, kGauss };
inline constexpr base::EnumName<LinkingMethod> kLinkingMethodNames[] = {
    {LinkingMethod::kAuto, "auto"},
    {LinkingMethod::kCrossings, "crossings"},
    {LinkingMethod::kGauss, "gauss"}};
constexpr std::span<const base::EnumName<LinkingMethod>> EnumNames(LinkingMethod) {
  return kLinkingMethodNames;
}

struct LinkingResult {
  double gauss_integral = 0.0;   // T (NaN when method is kCrossings)
  double error_bound = 0.0;      // B (0 for crossings: every sign is certified)
  double distance = 0.0;         // |T − round(T)|
  long long linking_number = 0;  // round(T) or ½ Σ ε; meaningful only when certified
  long long degenerate_pairs = 0;
  long long crossings = 0;  // crossings of A with B in the projection (kCrossings)
  // Direction projected along (kCrossings, certified); zero otherwise.
  Eigen::Vector3d projection = Eigen::Vector3d::Zero();
  int segments_a = 0, segments_b = 0;
  LinkingMethod method = LinkingMethod::kGauss;  // the method that produced this result
  LinkingStatus status = LinkingStatus::kUncertain;
};

// Gauss linking number of two closed chains: T by StreamWritheSums (signed variant), rounded when
// kCertified (distance ≤ B < 1/2 and no degenerate pair). A last point within the closing gap of
// the first is moved onto it (on a copy) first: the number is that of the exactly closed polygons.
// Throws std::invalid_argument naming the chain ("A" or "B") when one is not closed, or as
// WritheMatrix for a bad chain.
LinkingResult LinkingNumber(const Chain& a, const Chain& b,
                            const WritheStreamOptions& options = {});

}  // namespace topology
