// Body of the SIMD writhe kernel (topology/internal/writhe_tile.h), included by one .cc file per
// instruction set inside an anonymous namespace after it defines the 4-lane type V and:
//   Set1 Load Store Add Sub Mul Div Sqrt Lt Le Eq And Or AndNot Blend Abs Atan2 Any Count Iota
//   Transpose4.
// AndNot(m, a) = ~m & a; Blend(a, b, m) = m ? b : a; Atan2 is SLEEF's (≤ 3.5 ulp).
// Uses raw pointers and intrinsics only (no library templates), so that code compiled for AVX2
// cannot be merged into a caller compiled for the baseline instruction set.
//
// Every formula below repeats the scalar kernel of topology/writhe.cc operation for operation
// (same association, no FMA): X and Y are bitwise those of the scalar path.

constexpr double kTwoPiTile = 6.283185307179586476925286766559;

struct DirRow {  // unit vectors from one point of A to consecutive points of B, and lengths
  double *x, *y, *z, *n;
};

// Directions from point p (xyz) to points [q0, q0 + count) of B; count is a multiple of 4.
inline void Directions(const double* p, const topology::internal::TileArgs& t, int q0, int count,
                       const DirRow& d) {
  const V px = Set1(p[0]), py = Set1(p[1]), pz = Set1(p[2]), zero = Set1(0.0);
  const double *bx = t.bx + q0, *by = t.by + q0, *bz = t.bz + q0;
  for (int k = 0; k < count; k += 4) {
    const V rx = Sub(Load(bx + k), px), ry = Sub(Load(by + k), py), rz = Sub(Load(bz + k), pz);
    const V n = Sqrt(Add(Add(Mul(rx, rx), Mul(ry, ry)), Mul(rz, rz)));
    const V positive = Lt(zero, n);  // zero length: direction 0 (the pair is degenerate anyway)
    Store(d.x + k, And(positive, Div(rx, n)));
    Store(d.y + k, And(positive, Div(ry, n)));
    Store(d.z + k, And(positive, Div(rz, n)));
    Store(d.n + k, n);
  }
}

inline V Dot(V ax, V ay, V az, V bx, V by, V bz) {
  return Add(Add(Mul(ax, bx), Mul(ay, by)), Mul(az, bz));
}

// Four pairs (i, j0 + l), l < 4, from direction rows d0 (from a_i) and d1 (from a_{i+1}) at local
// index k: v1 = d0[k], v2 = d0[k+1], v3 = d1[k+1], v4 = d1[k]. Returns w and (X, Y). With kGrad,
// g[0..11] receives [∂w/∂a_i; ∂w/∂a_{i+1}; ∂w/∂b_j; ∂w/∂b_{j+1}] (x, y, z each), as the scalar
// kernel's Jacobian column.
struct Quad {
  V w, x, y;
};
template <bool kGrad>
inline Quad PairQuad(const DirRow& d0, const DirRow& d1, int k, V degenerate, V tol,
                     bool unsigned_variant, V* g) {
  const V x1 = Load(d0.x + k), y1 = Load(d0.y + k), z1 = Load(d0.z + k);
  const V x2 = Load(d0.x + k + 1), y2 = Load(d0.y + k + 1), z2 = Load(d0.z + k + 1);
  const V x3 = Load(d1.x + k + 1), y3 = Load(d1.y + k + 1), z3 = Load(d1.z + k + 1);
  const V x4 = Load(d1.x + k), y4 = Load(d1.y + k), z4 = Load(d1.z + k);
  const V n1 = Load(d0.n + k), n2 = Load(d0.n + k + 1), n3 = Load(d1.n + k + 1),
          n4 = Load(d1.n + k);
  degenerate = Or(degenerate, Or(Or(Lt(n1, tol), Lt(n2, tol)), Or(Lt(n3, tol), Lt(n4, tol))));
  // c23 = v2 × v3, c34 = v3 × v4.
  const V c23x = Sub(Mul(y2, z3), Mul(z2, y3)), c23y = Sub(Mul(z2, x3), Mul(x2, z3)),
          c23z = Sub(Mul(x2, y3), Mul(y2, x3));
  const V c34x = Sub(Mul(y3, z4), Mul(z3, y4)), c34y = Sub(Mul(z3, x4), Mul(x3, z4)),
          c34z = Sub(Mul(x3, y4), Mul(y3, x4));
  const V d12 = Dot(x1, y1, z1, x2, y2, z2), d23 = Dot(x2, y2, z2, x3, y3, z3);
  const V d31 = Dot(x3, y3, z3, x1, y1, z1), d34 = Dot(x3, y3, z3, x4, y4, z4);
  const V d41 = Dot(x4, y4, z4, x1, y1, z1);
  const V one = Set1(1.0);
  const V t1y = Dot(x1, y1, z1, c23x, c23y, c23z), t1x = Add(Add(Add(one, d12), d23), d31);
  const V t2y = Dot(x1, y1, z1, c34x, c34y, c34z), t2x = Add(Add(Add(one, d31), d34), d41);
  const V big_x = Sub(Mul(t1x, t2x), Mul(t1y, t2y));
  const V big_y = Add(Mul(t1x, t2y), Mul(t1y, t2x));
  const V mag2 = Add(Mul(big_x, big_x), Mul(big_y, big_y));
  const V cut = And(Lt(big_x, Set1(0.0)), Le(Abs(big_y), Mul(Set1(1e-14), Abs(big_x))));
  degenerate = Or(degenerate, Or(Lt(mag2, Set1(1e-24)), cut));
  Quad q;
  q.x = Blend(big_x, one, degenerate);
  q.y = AndNot(degenerate, big_y);
  q.w = Mul(Atan2(q.y, q.x), Set1(-1.0 / kTwoPiTile));
  V scale = one;
  if (unsigned_variant) {  // |Ω| = 4π|w|
    scale = Blend(Set1(2.0 * kTwoPiTile), Set1(-2.0 * kTwoPiTile), Lt(q.w, Set1(0.0)));
    q.w = Mul(q.w, scale);
  }
  if constexpr (kGrad) {
    // dθ_t/dv = (x ∂y/∂v − y ∂x/∂v)/(x² + y²) for both triangles, then through v = r/|r|.
    const V floor = Set1(1e-20), minus_one = Set1(-1.0);
    const V den1 = Add(Mul(t1x, t1x), Mul(t1y, t1y)), den2 = Add(Mul(t2x, t2x), Mul(t2y, t2y));
    // s = −1/(2π den) where den > floor, else 0 (the scalar kernel's −1.0 / (kTwoPi * den)).
    const V s1 = And(Lt(floor, den1), Div(minus_one, Mul(Set1(kTwoPiTile), den1)));
    const V s2 = And(Lt(floor, den2), Div(minus_one, Mul(Set1(kTwoPiTile), den2)));
    const V ax1 = Mul(s1, t1x), ay1 = Mul(s1, t1y), ax2 = Mul(s2, t2x), ay2 = Mul(s2, t2y);
    // c31 = v3 × v1, c12 = v1 × v2, c41 = v4 × v1, c13 = −c31.
    const V c31x = Sub(Mul(y3, z1), Mul(z3, y1)), c31y = Sub(Mul(z3, x1), Mul(x3, z1)),
            c31z = Sub(Mul(x3, y1), Mul(y3, x1));
    const V c12x = Sub(Mul(y1, z2), Mul(z1, y2)), c12y = Sub(Mul(z1, x2), Mul(x1, z2)),
            c12z = Sub(Mul(x1, y2), Mul(y1, x2));
    const V c41x = Sub(Mul(y4, z1), Mul(z4, y1)), c41y = Sub(Mul(z4, x1), Mul(x4, z1)),
            c41z = Sub(Mul(x4, y1), Mul(y4, x1));
    const V zero = Set1(0.0);
    const V c13x = Sub(zero, c31x), c13y = Sub(zero, c31y), c13z = Sub(zero, c31z);
    // gv1 = ax1 c23 − ay1 (v2 + v3) + ax2 c34 − ay2 (v3 + v4), left to right, per component.
    const V gv1x =
        Sub(Add(Sub(Mul(ax1, c23x), Mul(ay1, Add(x2, x3))), Mul(ax2, c34x)), Mul(ay2, Add(x3, x4)));
    const V gv1y =
        Sub(Add(Sub(Mul(ax1, c23y), Mul(ay1, Add(y2, y3))), Mul(ax2, c34y)), Mul(ay2, Add(y3, y4)));
    const V gv1z =
        Sub(Add(Sub(Mul(ax1, c23z), Mul(ay1, Add(z2, z3))), Mul(ax2, c34z)), Mul(ay2, Add(z3, z4)));
    const V gv2x = Sub(Mul(ax1, c31x), Mul(ay1, Add(x1, x3)));
    const V gv2y = Sub(Mul(ax1, c31y), Mul(ay1, Add(y1, y3)));
    const V gv2z = Sub(Mul(ax1, c31z), Mul(ay1, Add(z1, z3)));
    const V gv3x =
        Sub(Add(Sub(Mul(ax1, c12x), Mul(ay1, Add(x1, x2))), Mul(ax2, c41x)), Mul(ay2, Add(x1, x4)));
    const V gv3y =
        Sub(Add(Sub(Mul(ax1, c12y), Mul(ay1, Add(y1, y2))), Mul(ax2, c41y)), Mul(ay2, Add(y1, y4)));
    const V gv3z =
        Sub(Add(Sub(Mul(ax1, c12z), Mul(ay1, Add(z1, z2))), Mul(ax2, c41z)), Mul(ay2, Add(z1, z4)));
    const V gv4x = Sub(Mul(ax2, c13x), Mul(ay2, Add(x1, x3)));
    const V gv4y = Sub(Mul(ax2, c13y), Mul(ay2, Add(y1, y3)));
    const V gv4z = Sub(Mul(ax2, c13z), Mul(ay2, Add(z1, z3)));
    // g_k = (gv_k − v_k (v_k · gv_k)) · (1 / n_k), zero for a degenerate pair.
    auto project = [&](V vx, V vy, V vz, V gx, V gy, V gz, V n, V* out) {
      const V d = Dot(vx, vy, vz, gx, gy, gz), inv_n = Div(one, n);
      out[0] = AndNot(degenerate, Mul(Sub(gx, Mul(vx, d)), inv_n));
      out[1] = AndNot(degenerate, Mul(Sub(gy, Mul(vy, d)), inv_n));
      out[2] = AndNot(degenerate, Mul(Sub(gz, Mul(vz, d)), inv_n));
    };
    V g1[3], g2[3], g3[3], g4[3];
    project(x1, y1, z1, gv1x, gv1y, gv1z, n1, g1);
    project(x2, y2, z2, gv2x, gv2y, gv2z, n2, g2);
    project(x3, y3, z3, gv3x, gv3y, gv3z, n3, g3);
    project(x4, y4, z4, gv4x, gv4y, gv4z, n4, g4);
    // r1 = b_j − a_i, r2 = b_{j+1} − a_i, r3 = b_{j+1} − a_{i+1}, r4 = b_j − a_{i+1}.
    for (int c = 0; c < 3; ++c) {
      g[c] = Mul(Sub(zero, Add(g1[c], g2[c])), scale);
      g[3 + c] = Mul(Sub(zero, Add(g3[c], g4[c])), scale);
      g[6 + c] = Mul(Add(g1[c], g4[c]), scale);
      g[9 + c] = Mul(Add(g2[c], g3[c]), scale);
    }
  }
  return q;
}

// min(1, 1/|Z|) per lane, with the square root only when some lane has |Z| < 1 (rare).
inline V InverseMagnitude(const Quad& q) {
  const V one = Set1(1.0);
  const V m2 = Add(Mul(q.x, q.x), Mul(q.y, q.y));
  const V near = Lt(m2, one);
  if (!Any(near)) return one;
  return Blend(one, Div(one, Sqrt(m2)), near);
}

inline V IsReportedZero(const Quad& q) { return And(Eq(q.x, Set1(1.0)), Eq(q.y, Set1(0.0))); }

// One row i over the tile's segments [c0, c1).
inline void TileRow(const topology::internal::TileArgs& t, int i, int c0, int c1, const DirRow& d0,
                    const DirRow& d1) {
  const V degenerate_a = t.a_degenerate[i] ? Eq(Set1(0.0), Set1(0.0)) : Set1(0.0);
  const V tol = Set1(t.degenerate_length), one = Set1(1.0);
  const double* b_degenerate = t.b_degenerate;
  const auto& out = t.out;
  if (out.jacobian != nullptr) {
    double* row = out.dense + (i - out.dense_row0);
    double* jac = out.jacobian + 12 * (static_cast<long long>(i) * t.cols);
    for (int j = c0; j < c1; j += 4) {
      const V deg = Or(degenerate_a, Eq(Load(b_degenerate + j), one));
      V g[12];
      const Quad q = PairQuad<true>(d0, d1, j - c0, deg, tol, t.unsigned_variant, g);
      alignas(32) double w[4], gl[12][4];
      Store(w, q.w);
      const int lanes = c1 - j < 4 ? c1 - j : 4;
      for (int l = 0; l < lanes; ++l) row[(j + l - out.dense_col0) * out.ld] = w[l];
      double* block = jac + 12 * static_cast<long long>(j);  // 4 consecutive pairs, 48 doubles
      if (lanes == 4) {
        for (int c = 0; c < 12; c += 4) {  // 4×4 transposes: lane l's column is 12 contiguous
          V r0 = g[c], r1 = g[c + 1], r2 = g[c + 2], r3 = g[c + 3];
          Transpose4(&r0, &r1, &r2, &r3);
          Store(block + c, r0);
          Store(block + 12 + c, r1);
          Store(block + 24 + c, r2);
          Store(block + 36 + c, r3);
        }
      } else {
        for (int c = 0; c < 12; ++c) Store(gl[c], g[c]);
        for (int l = 0; l < lanes; ++l) {
          for (int c = 0; c < 12; ++c) block[12 * l + c] = gl[c][l];
        }
      }
    }
    return;
  }
  if (out.dense != nullptr) {
    double* row = out.dense + (i - out.dense_row0);
    for (int j = c0; j < c1; j += 4) {
      const V deg = Or(degenerate_a, Eq(Load(b_degenerate + j), one));
      const Quad q = PairQuad<false>(d0, d1, j - c0, deg, tol, t.unsigned_variant, nullptr);
      alignas(32) double w[4];
      Store(w, q.w);
      const int lanes = c1 - j < 4 ? c1 - j : 4;
      for (int l = 0; l < lanes; ++l) row[(j + l - out.dense_col0) * out.ld] = w[l];
    }
    return;
  }
  const int r = i - t.row_begin;
  double* lane_sum = out.lane_sum + 4 * r;
  double* lane_abs = out.lane_abs + 4 * r;
  double* lane_inv = out.lane_inv_mag + 4 * r;
  V s = Load(lane_sum), a = Load(lane_abs), inv = Load(lane_inv);
  long long zeros = 0;
  const int full_end = t.cols & ~3;  // quads below it are summed lane-wise
  const int quad_end = c1 < full_end ? c1 : full_end;
  int j = c0;
  for (; j < quad_end; j += 4) {
    const V deg = Or(degenerate_a, Eq(Load(b_degenerate + j), one));
    const Quad q = PairQuad<false>(d0, d1, j - c0, deg, tol, t.unsigned_variant, nullptr);
    s = Add(s, q.w);
    a = Add(a, Abs(q.w));
    inv = Add(inv, InverseMagnitude(q));
    zeros += Count(IsReportedZero(q));
  }
  double tail_w[4] = {0.0, 0.0, 0.0, 0.0};
  int tail = 0;
  if (j < c1) {  // the tail: the last j ≥ full_end (< 4 pairs) go to lane 0 in order
    const V deg = Or(degenerate_a, Eq(Load(b_degenerate + j), one));
    const Quad q = PairQuad<false>(d0, d1, j - c0, deg, tol, t.unsigned_variant, nullptr);
    tail = c1 - j;
    const V valid = Lt(Add(Iota(), Set1(static_cast<double>(j))), Set1(static_cast<double>(c1)));
    inv = Add(inv, And(valid, InverseMagnitude(q)));
    zeros += Count(And(valid, IsReportedZero(q)));
    Store(tail_w, q.w);
  }
  Store(lane_sum, s);
  Store(lane_abs, a);
  Store(lane_inv, inv);
  for (int l = 0; l < tail; ++l) {
    lane_sum[0] += tail_w[l];
    lane_abs[0] += tail_w[l] < 0.0 ? -tail_w[l] : tail_w[l];
  }
  out.degenerate[r] += zeros;
}

inline void RunTiles(const topology::internal::TileArgs& t) {
  constexpr int kStride = topology::internal::kTileCols + 16;
  DirRow d0{t.scratch, t.scratch + kStride, t.scratch + 2 * kStride, t.scratch + 3 * kStride};
  DirRow d1{t.scratch + 4 * kStride, t.scratch + 5 * kStride, t.scratch + 6 * kStride,
            t.scratch + 7 * kStride};
  for (int c0 = t.col_begin; c0 < t.col_end; c0 += topology::internal::kTileCols) {
    const int c1 = t.col_end < c0 + topology::internal::kTileCols
                       ? t.col_end
                       : c0 + topology::internal::kTileCols;
    // Quads start at local k ≤ c1 − c0 − 1 and read directions k..k + 4.
    const int count = ((c1 - c0 + 3) & ~3) + 4;
    Directions(t.a + 3 * static_cast<long long>(t.row_begin), t, c0, count, d0);
    for (int i = t.row_begin; i < t.row_end; ++i) {
      Directions(t.a + 3 * (static_cast<long long>(i) + 1), t, c0, count, d1);
      TileRow(t, i, c0, c1, d0, d1);
      const DirRow tmp = d0;
      d0 = d1;
      d1 = tmp;
    }
  }
}
