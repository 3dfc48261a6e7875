// The SIMD writhe kernel (topology/internal/writhe_tile.h) for the x86-64 baseline: each
// 4-lane value is two __m128d (SSE2), the atan2 SLEEF's 2-lane one. Also the level dispatch.
#include <emmintrin.h>
#include <sleef.h>

#include <atomic>

#include "topology/internal/writhe_tile.h"

namespace topology::internal {
namespace {

struct V {
  __m128d lo, hi;
};
inline V Set1(double x) { return {_mm_set1_pd(x), _mm_set1_pd(x)}; }
inline V Load(const double* p) { return {_mm_loadu_pd(p), _mm_loadu_pd(p + 2)}; }
inline void Store(double* p, V a) {
  _mm_storeu_pd(p, a.lo);
  _mm_storeu_pd(p + 2, a.hi);
}
inline V Add(V a, V b) { return {_mm_add_pd(a.lo, b.lo), _mm_add_pd(a.hi, b.hi)}; }
inline V Sub(V a, V b) { return {_mm_sub_pd(a.lo, b.lo), _mm_sub_pd(a.hi, b.hi)}; }
inline V Mul(V a, V b) { return {_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(a.hi, b.hi)}; }
inline V Div(V a, V b) { return {_mm_div_pd(a.lo, b.lo), _mm_div_pd(a.hi, b.hi)}; }
inline V Sqrt(V a) { return {_mm_sqrt_pd(a.lo), _mm_sqrt_pd(a.hi)}; }
inline V Lt(V a, V b) { return {_mm_cmplt_pd(a.lo, b.lo), _mm_cmplt_pd(a.hi, b.hi)}; }
inline V Le(V a, V b) { return {_mm_cmple_pd(a.lo, b.lo), _mm_cmple_pd(a.hi, b.hi)}; }
inline V Eq(V a, V b) { return {_mm_cmpeq_pd(a.lo, b.lo), _mm_cmpeq_pd(a.hi, b.hi)}; }
inline V And(V a, V b) { return {_mm_and_pd(a.lo, b.lo), _mm_and_pd(a.hi, b.hi)}; }
inline V Or(V a, V b) { return {_mm_or_pd(a.lo, b.lo), _mm_or_pd(a.hi, b.hi)}; }
inline V AndNot(V m, V a) { return {_mm_andnot_pd(m.lo, a.lo), _mm_andnot_pd(m.hi, a.hi)}; }
inline V Blend(V a, V b, V m) { return Or(And(m, b), AndNot(m, a)); }
inline V Abs(V a) { return AndNot(Set1(-0.0), a); }
inline V Atan2(V y, V x) { return {Sleef_atan2d2_u35(y.lo, x.lo), Sleef_atan2d2_u35(y.hi, x.hi)}; }
inline bool Any(V m) { return (_mm_movemask_pd(m.lo) | _mm_movemask_pd(m.hi)) != 0; }
inline int Count(V m) {
  const int bits = _mm_movemask_pd(m.lo) | (_mm_movemask_pd(m.hi) << 2);
  return __builtin_popcount(static_cast<unsigned>(bits));
}
inline V Iota() { return {_mm_set_pd(1.0, 0.0), _mm_set_pd(3.0, 2.0)}; }
// (r0, r1, r2, r3) as rows of a 4×4 matrix → its columns.
inline void Transpose4(V* r0, V* r1, V* r2, V* r3) {
  const V a = *r0, b = *r1, c = *r2, d = *r3;
  *r0 = {_mm_unpacklo_pd(a.lo, b.lo), _mm_unpacklo_pd(c.lo, d.lo)};
  *r1 = {_mm_unpackhi_pd(a.lo, b.lo), _mm_unpackhi_pd(c.lo, d.lo)};
  *r2 = {_mm_unpacklo_pd(a.hi, b.hi), _mm_unpacklo_pd(c.hi, d.hi)};
  *r3 = {_mm_unpackhi_pd(a.hi, b.hi), _mm_unpackhi_pd(c.hi, d.hi)};
}

#include "topology/internal/writhe_tile_impl.h"

std::atomic<SimdLevel> g_level{SimdLevel::kAuto};

}  // namespace

void WritheTileSse2(const TileArgs& t) { RunTiles(t); }

void SetSimdLevel(SimdLevel level) { g_level.store(level); }

SimdLevel ActiveSimdLevel() {
  const SimdLevel level = g_level.load(std::memory_order_relaxed);
  if (level != SimdLevel::kAuto) return level;
  return __builtin_cpu_supports("avx2") ? SimdLevel::kAvx2 : SimdLevel::kSse2;
}

void WritheTile(const TileArgs& t) {
  if (ActiveSimdLevel() == SimdLevel::kAvx2) {
    WritheTileAvx2(t);
  } else {
    WritheTileSse2(t);
  }
}

}  // namespace topology::internal
