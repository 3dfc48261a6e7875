// The SIMD writhe kernel (topology/internal/writhe_tile.h) for AVX2: 4 lanes of __m256d. This
// file alone is compiled with -mavx2 -ffp-contract=off (topology/CMakeLists.txt) and is entered
// only after a CPU check; it uses intrinsics and raw pointers only.
#include <immintrin.h>
#include <sleef.h>

#include "topology/internal/writhe_tile.h"

namespace topology::internal {
namespace {

using V = __m256d;
inline V Set1(double x) { return _mm256_set1_pd(x); }
inline V Load(const double* p) { return _mm256_loadu_pd(p); }
inline void Store(double* p, V a) { _mm256_storeu_pd(p, a); }
inline V Add(V a, V b) { return _mm256_add_pd(a, b); }
inline V Sub(V a, V b) { return _mm256_sub_pd(a, b); }
inline V Mul(V a, V b) { return _mm256_mul_pd(a, b); }
inline V Div(V a, V b) { return _mm256_div_pd(a, b); }
inline V Sqrt(V a) { return _mm256_sqrt_pd(a); }
inline V Lt(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }
inline V Le(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
inline V Eq(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_EQ_OQ); }
inline V And(V a, V b) { return _mm256_and_pd(a, b); }
inline V Or(V a, V b) { return _mm256_or_pd(a, b); }
inline V AndNot(V m, V a) { return _mm256_andnot_pd(m, a); }
inline V Blend(V a, V b, V m) { return _mm256_blendv_pd(a, b, m); }
inline V Abs(V a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
inline V Atan2(V y, V x) { return Sleef_atan2d4_u35avx2(y, x); }
inline bool Any(V m) { return _mm256_movemask_pd(m) != 0; }
inline int Count(V m) { return __builtin_popcount(static_cast<unsigned>(_mm256_movemask_pd(m))); }
inline V Iota() { return _mm256_set_pd(3.0, 2.0, 1.0, 0.0); }
// (r0, r1, r2, r3) as rows of a 4×4 matrix → its columns.
inline void Transpose4(V* r0, V* r1, V* r2, V* r3) {
  const V t0 = _mm256_unpacklo_pd(*r0, *r1), t1 = _mm256_unpackhi_pd(*r0, *r1);
  const V t2 = _mm256_unpacklo_pd(*r2, *r3), t3 = _mm256_unpackhi_pd(*r2, *r3);
  *r0 = _mm256_permute2f128_pd(t0, t2, 0x20);
  *r1 = _mm256_permute2f128_pd(t1, t3, 0x20);
  *r2 = _mm256_permute2f128_pd(t0, t2, 0x31);
  *r3 = _mm256_permute2f128_pd(t1, t3, 0x31);
}

#include "topology/internal/writhe_tile_impl.h"

}  // namespace

void WritheTileAvx2(const TileArgs& t) { RunTiles(t); }

}  // namespace topology::internal
