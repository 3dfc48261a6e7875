// Internal to the topology module: the SIMD writhe kernel for values only (no gradient), blocked
// for the L1 cache. It evaluates exactly the closed form of topology/writhe.h (Klenin &
// Langowski 2000; two Van Oosterom–Strackee triangles combined into one complex argument
// Z = X + iY, W[i][j] = −arg Z / 2π) with the same operations in the same order as the scalar
// kernel, four segment pairs per step:
//   AVX2 (4 lanes, SLEEF atan2d4) when the CPU has it, else SSE2 (2 × 2 lanes, SLEEF atan2d2).
// No FMA contraction; the products are associated as written here, the scalar kernel's through
// Eigen, so entries agree with it to a few ulp (tests: ≤ 1e-12 relative), not bitwise.
//
// Work is a rectangle of rows [row_begin, row_end) of A × segments [col_begin, col_end) of B,
// walked in column tiles of kTileCols segments; inside a tile the unit directions from a_i to the
// tile's points of B stay in L1 while i advances. col_begin must be a multiple of 4.
#pragma once

#include <cstdint>
#include <vector>

#include "topology/polyline.h"
#include "topology/writhe.h"

namespace topology::internal {

inline constexpr int kTileCols = 256;  // segments of B per tile (multiple of 4)
// Callers use the scalar kernel when B has fewer segments than this (lanes would idle).
inline constexpr int kMinSimdCols = 4;
// Dense matrices with fewer pairs than this use the scalar kernel (topology/writhe.cc Compute).
inline constexpr int kMinSimdPairs = 4096;

// Chain B as structure of arrays, for TileArgs: four arrays of `stride` = N_B + 8 doubles at
// soa[0], soa[stride], soa[2·stride], soa[3·stride]: x, y, z of the points (padded with copies of
// the last point so that 4-lane loads past the end stay in bounds) and a flag per segment, 1.0
// when shorter than the degenerate length, else 0.0 (padded with 1.0). Returns the stride.
int FillSoaChain(const Chain& c, double degenerate_length, std::vector<double>* soa);
// A's per-segment flags (1 when shorter than the degenerate length).
void FillDegenerateSegments(const Chain& c, double degenerate_length,
                            std::vector<std::uint8_t>* flags);

// Per-row outputs. Sums mode: lane k of row r (r = i − row_begin) accumulates the entries with
// j ≡ k (mod 4) below the last full group of four of B's segments in increasing j, and the rest
// (the tail) is added to lane 0 in increasing j: exactly RowSumSink's order, so a row's sum does
// not depend on the tiling or the rectangle. Dense mode writes W[i][j] to dense[i + j·ld].
struct TileOutput {
  double* lane_sum = nullptr;       // 4 per row: Σ W[i][j]
  double* lane_abs = nullptr;       // 4 per row: Σ |W[i][j]|
  double* lane_inv_mag = nullptr;   // 4 per row: Σ min(1, 1/|Z_ij|) (for the error bound)
  long long* degenerate = nullptr;  // 1 per row: pairs with Z = 1 exactly (reported as 0)
  // Dense mode when not null: W[i][j] at dense[(i − dense_row0) + (j − dense_col0)·ld].
  double* dense = nullptr;
  long long ld = 0;
  int dense_row0 = 0, dense_col0 = 0;
  // Dense mode with gradient when also not null: WritheJacobian::pair data, 12 per pair at
  // 12·(i·cols + j); the values still go to `dense`.
  double* jacobian = nullptr;
};

struct TileArgs {
  const double* a = nullptr;                   // A's points, xyz interleaved (Chain::data())
  const std::uint8_t* a_degenerate = nullptr;  // per segment of A
  const double *bx = nullptr, *by = nullptr, *bz = nullptr;  // B (FillSoaChain)
  const double* b_degenerate = nullptr;
  void SetB(const std::vector<double>& soa, int stride) {
    bx = soa.data();
    by = bx + stride;
    bz = by + stride;
    b_degenerate = bz + stride;
  }
  int row_begin = 0, row_end = 0, col_begin = 0, col_end = 0;
  int cols = 0;  // all segments of B (for the tail rule)
  double degenerate_length = 1e-12;
  bool unsigned_variant = false;
  double* scratch = nullptr;  // TileScratchSize() doubles, 32-byte aligned not required
  TileOutput out;
};
inline constexpr int TileScratchSize() { return 8 * (kTileCols + 16); }

enum class SimdLevel { kAuto, kScalar, kSse2, kAvx2 };
// Which kernel the value paths use: kAuto picks AVX2 when the CPU has it. kScalar selects the
// per-row scalar kernel (the oracle). For tests and benchmarks; not thread-safe against running
// kernels.
void SetSimdLevel(SimdLevel level);
SimdLevel ActiveSimdLevel();  // the resolved level (never kAuto)

void WritheTileAvx2(const TileArgs& t);  // only on a CPU with AVX2
void WritheTileSse2(const TileArgs& t);
void WritheTile(const TileArgs& t);  // the active level (not kScalar)

}  // namespace topology::internal
