#include "topology/writhe.h"

#include <emmintrin.h>
#include <sleef.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "topology/internal/writhe_rows.h"
#include "topology/internal/writhe_tile.h"
#include "topology/writhe_stream.h"

namespace topology {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
// Floor for x² + y² of one spherical triangle in the gradient: below it the triangle is degenerate
// (its vertices are antipodal or coincide) and its derivative is not defined.
constexpr double kTriangleFloor = 1e-20;

using Eigen::Vector3d;

// The per-pair kernel on precomputed unit directions. With a_0, a_1 the endpoints of the A segment
// and b_0, b_1 those of the B segment:
//   v1 = dir(b0 − a0), v2 = dir(b1 − a0), v3 = dir(b1 − a1), v4 = dir(b0 − a1), n_k = |r_k|.
// Spherical quadrilateral (v1, v2, v3, v4) = triangles (v1, v2, v3) + (v1, v3, v4); each triangle's
// half solid angle is θ = atan2(y, x) with y = det, x = 1 + sum of pairwise dots. The pair's GLI
// is −(θ1 + θ2)/(2π) for the orientation convention of the header (checked against quadrature).
struct PairResult {
  Vector3d g1, g2, g3, g4;  // ∂w/∂r_k for r1..r4 (only when requested)
};

// Fills (X, Y) with X + iY = (x1 + i y1)(x2 + i y2), so that w = −atan2(Y, X)/(2π); the atan2 is
// evaluated later for a whole row at once (vectorised). Degenerate pairs get (1, 0), i.e. w = 0.
template <bool kGrad>
inline void PairKernel(const Vector3d& v1, const Vector3d& v2, const Vector3d& v3,
                       const Vector3d& v4, double n1, double n2, double n3, double n4,
                       double* out_x, double* out_y, PairResult* out) {
  const Vector3d c23 = v2.cross(v3);
  const Vector3d c34 = v3.cross(v4);
  const double d12 = v1.dot(v2), d23 = v2.dot(v3), d31 = v3.dot(v1);
  const double d34 = v3.dot(v4), d41 = v4.dot(v1);
  const double y1 = v1.dot(c23), x1 = 1.0 + d12 + d23 + d31;
  const double y2 = v1.dot(c34), x2 = 1.0 + d31 + d34 + d41;
  const double big_x = x1 * x2 - y1 * y2;
  const double big_y = x1 * y2 + y1 * x2;
  // Coplanar crossing or overlapping collinear segments: the value sits on the branch cut (±1/2)
  // or is 0/0; both mean "intersecting", reported as 0.
  const double mag2 = big_x * big_x + big_y * big_y;
  if (mag2 < 1e-24 || (big_x < 0.0 && std::abs(big_y) <= 1e-14 * std::abs(big_x))) {
    if constexpr (kGrad) out->g1 = out->g2 = out->g3 = out->g4 = Vector3d::Zero();
    *out_x = 1.0;
    *out_y = 0.0;
    return;
  }
  *out_x = big_x;
  *out_y = big_y;
  if constexpr (kGrad) {
    // dθ_t/dv = (x ∂y/∂v − y ∂x/∂v)/(x² + y²), for both triangles; then through v = r/|r|.
    const double den1 = x1 * x1 + y1 * y1, den2 = x2 * x2 + y2 * y2;
    const double s1 = den1 > kTriangleFloor ? -1.0 / (kTwoPi * den1) : 0.0;
    const double s2 = den2 > kTriangleFloor ? -1.0 / (kTwoPi * den2) : 0.0;
    const double ax1 = s1 * x1, ay1 = s1 * y1, ax2 = s2 * x2, ay2 = s2 * y2;
    const Vector3d c31 = v3.cross(v1), c12 = v1.cross(v2), c41 = v4.cross(v1), c13 = -c31;
    const Vector3d gv1 = ax1 * c23 - ay1 * (v2 + v3) + ax2 * c34 - ay2 * (v3 + v4);
    const Vector3d gv2 = ax1 * c31 - ay1 * (v1 + v3);
    const Vector3d gv3 = ax1 * c12 - ay1 * (v1 + v2) + ax2 * c41 - ay2 * (v1 + v4);
    const Vector3d gv4 = ax2 * c13 - ay2 * (v1 + v3);
    out->g1 = (gv1 - v1 * v1.dot(gv1)) / n1;
    out->g2 = (gv2 - v2 * v2.dot(gv2)) / n2;
    out->g3 = (gv3 - v3 * v3.dot(gv3)) / n3;
    out->g4 = (gv4 - v4 * v4.dot(gv4)) / n4;
  }
}

// out[k] = −atan2(y[k], x[k])/(2π) for k < n, two lanes at a time (SLEEF, 3.5 ULP).
void RowAngles(const double* y, const double* x, int n, double* out) {
  const __m128d scale = _mm_set1_pd(-1.0 / kTwoPi);
  int k = 0;
  for (; k + 1 < n; k += 2) {
    const __m128d a = Sleef_atan2d2_u35(_mm_loadu_pd(y + k), _mm_loadu_pd(x + k));
    _mm_storeu_pd(out + k, _mm_mul_pd(a, scale));
  }
  for (; k < n; ++k) out[k] = -std::atan2(y[k], x[k]) / kTwoPi;
}

// Unit vectors and lengths from point a to every point of b.
void FillDirections(const Vector3d& a, const Chain& b, std::vector<Vector3d>* dir,
                    std::vector<double>* len) {
  const Eigen::Index nb = b.cols();
  dir->resize(nb);
  len->resize(nb);
  for (Eigen::Index q = 0; q < nb; ++q) {
    const Vector3d r = b.col(q) - a;
    const double n = r.norm();
    (*len)[q] = n;
    (*dir)[q] = n > 0.0 ? Vector3d(r / n) : Vector3d::Zero();
  }
}

// Shared driver: rows [row_begin, row_end) of A, advancing two direction rows at a time. Each
// finished row is in ws->w_row (values), ws->x_row / ws->y_row (atan2 arguments) when
// `emit(i)` is called. With kGrad, jac->pair (already sized) receives the gradient columns.
template <bool kGrad, typename Emit>
void ComputeRows(const Chain& a, const Chain& b, const WritheOptions& opt, int row_begin,
                 int row_end, WritheJacobian* jac, WritheWorkspace* ws, Emit&& emit) {
  const int cols = static_cast<int>(b.cols()) - 1;
  const double tol = opt.degenerate_length;
  const bool unsigned_variant = opt.variant == WritheVariant::kUnsignedSolidAngle;

  ws->b_degenerate.resize(cols);
  for (int j = 0; j < cols; ++j) ws->b_degenerate[j] = (b.col(j + 1) - b.col(j)).norm() < tol;
  const auto& b_degenerate = ws->b_degenerate;

  ws->x_row.resize(cols);
  ws->y_row.resize(cols);
  ws->w_row.resize(cols);
  FillDirections(a.col(row_begin), b, &ws->dir_row0, &ws->len_row0);
  PairResult pr;
  for (int i = row_begin; i < row_end; ++i) {
    FillDirections(a.col(i + 1), b, &ws->dir_row1, &ws->len_row1);
    const auto& d0 = ws->dir_row0;
    const auto& d1 = ws->dir_row1;
    const auto& l0 = ws->len_row0;
    const auto& l1 = ws->len_row1;
    const bool a_degenerate = (a.col(i + 1) - a.col(i)).norm() < tol;
    // Pass 1: (X, Y) per pair, and the gradient (which needs no angle).
    for (int j = 0; j < cols; ++j) {
      const double n1 = l0[j], n2 = l0[j + 1], n3 = l1[j + 1], n4 = l1[j];
      const bool degenerate =
          a_degenerate || b_degenerate[j] || n1 < tol || n2 < tol || n3 < tol || n4 < tol;
      if (!degenerate) {
        PairKernel<kGrad>(d0[j], d0[j + 1], d1[j + 1], d1[j], n1, n2, n3, n4, &ws->x_row[j],
                          &ws->y_row[j], &pr);
      } else {
        ws->x_row[j] = 1.0;
        ws->y_row[j] = 0.0;
        if constexpr (kGrad) pr.g1 = pr.g2 = pr.g3 = pr.g4 = Vector3d::Zero();
      }
      if constexpr (kGrad) {
        // r1 = b_j − a_i, r2 = b_{j+1} − a_i, r3 = b_{j+1} − a_{i+1}, r4 = b_j − a_{i+1}.
        auto col = jac->pair.col(static_cast<Eigen::Index>(i) * cols + j);
        col.template segment<3>(0) = -(pr.g1 + pr.g2);
        col.template segment<3>(3) = -(pr.g3 + pr.g4);
        col.template segment<3>(6) = pr.g1 + pr.g4;
        col.template segment<3>(9) = pr.g2 + pr.g3;
      }
    }
    // Pass 2: the angles of the whole row, vectorised.
    RowAngles(ws->y_row.data(), ws->x_row.data(), cols, ws->w_row.data());
    if (unsigned_variant) {
      for (int j = 0; j < cols; ++j) {
        const double scale = ws->w_row[j] < 0.0 ? -2.0 * kTwoPi : 2.0 * kTwoPi;  // |Ω| = 4π|w|
        ws->w_row[j] *= scale;
        if constexpr (kGrad) jac->pair.col(static_cast<Eigen::Index>(i) * cols + j) *= scale;
      }
    }
    emit(i);
    std::swap(ws->dir_row0, ws->dir_row1);
    std::swap(ws->len_row0, ws->len_row1);
  }
}

// The dense matrix (and Jacobian) of all rows.
template <bool kGrad>
void Compute(const Chain& a, const Chain& b, const WritheOptions& opt, Eigen::MatrixXd* w,
             WritheJacobian* jac, WritheWorkspace* ws) {
  internal::CheckWritheChain(a, "A");
  internal::CheckWritheChain(b, "B");
  const int rows = static_cast<int>(a.cols()) - 1, cols = static_cast<int>(b.cols()) - 1;
  w->resize(rows, cols);
  if constexpr (kGrad) {
    jac->rows = rows;
    jac->cols = cols;
    jac->pair.resize(12, static_cast<Eigen::Index>(rows) * cols);
  }
  WritheWorkspace local;
  if (ws == nullptr) ws = &local;
  // The SIMD kernel fills 4 pairs per step along B: with fewer than 4 segments of B (an arm
  // against one pole segment) most lanes would be wasted, and the scalar kernel is faster. Small
  // matrices (fewer than kMinSimdPairs pairs: the planners' features, evaluated thousands of times
  // per solve) keep the scalar kernel too, so planning results do not change with the CPU's
  // vector unit (the two kernels agree to ~1e-15 relative, not bitwise).
  if (cols >= internal::kMinSimdCols && rows * cols >= internal::kMinSimdPairs &&
      internal::ActiveSimdLevel() != internal::SimdLevel::kScalar) {
    internal::TileArgs t;
    t.a = a.data();
    internal::FillDegenerateSegments(a, opt.degenerate_length, &ws->a_degenerate);
    t.a_degenerate = ws->a_degenerate.data();
    t.SetB(ws->simd_b, internal::FillSoaChain(b, opt.degenerate_length, &ws->simd_b));
    t.row_end = rows;
    t.col_end = t.cols = cols;
    t.degenerate_length = opt.degenerate_length;
    t.unsigned_variant = opt.variant == WritheVariant::kUnsignedSolidAngle;
    ws->simd_scratch.resize(internal::TileScratchSize());
    t.scratch = ws->simd_scratch.data();
    t.out.dense = w->data();
    t.out.ld = rows;
    if constexpr (kGrad) t.out.jacobian = jac->pair.data();
    internal::WritheTile(t);
    return;
  }
  ComputeRows<kGrad>(a, b, opt, 0, rows, jac, ws, [&](int i) {
    for (int j = 0; j < cols; ++j) (*w)(i, j) = ws->w_row[j];
  });
}

}  // namespace

namespace internal {

void CheckWritheChain(const Chain& c, const char* name) {
  if (c.cols() < 2) {
    throw std::invalid_argument(std::string("writhe: chain ") + name +
                                " needs at least 2 points, got " + std::to_string(c.cols()));
  }
  if (!c.allFinite()) {
    throw std::invalid_argument(std::string("writhe: chain ") + name +
                                " has a non-finite coordinate");
  }
  if (c.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    throw std::invalid_argument(std::string("writhe: chain ") + name +
                                " has a coordinate beyond ±1e100 (squared lengths would overflow)");
  }
}

int FillSoaChain(const Chain& c, double degenerate_length, std::vector<double>* soa) {
  const int n = static_cast<int>(c.cols());
  const int stride = n + 8;
  soa->resize(4 * static_cast<size_t>(stride));
  double* p = soa->data();
  for (int k = 0; k < 3; ++k) {
    for (int q = 0; q < stride; ++q) p[k * stride + q] = c(k, q < n ? q : n - 1);
  }
  for (int j = 0; j < stride; ++j) {
    p[3 * stride + j] =
        j + 1 < n && !((c.col(j + 1) - c.col(j)).norm() < degenerate_length) ? 0.0 : 1.0;
  }
  return stride;
}

void FillDegenerateSegments(const Chain& c, double degenerate_length,
                            std::vector<std::uint8_t>* flags) {
  const int segments = static_cast<int>(c.cols()) - 1;
  flags->resize(segments);
  for (int i = 0; i < segments; ++i) {
    (*flags)[i] = (c.col(i + 1) - c.col(i)).norm() < degenerate_length ? 1 : 0;
  }
}

void WritheRows(const Chain& a, const Chain& b, const WritheOptions& options, int row_begin,
                int row_end, WritheWorkspace* ws, WritheRowSink* sink) {
  const int cols = static_cast<int>(b.cols()) - 1;
  ComputeRows<false>(a, b, options, row_begin, row_end, nullptr, ws, [&](int i) {
    sink->Row(i, ws->w_row.data(), ws->x_row.data(), ws->y_row.data(), cols);
  });
}

}  // namespace internal

double SegmentPairWrithe(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0,
                         const Vector3d& b1, const WritheOptions& options,
                         SegmentPairGradient* grad) {
  Chain a(3, 2), b(3, 2);
  a << a0, a1;
  b << b0, b1;
  Eigen::MatrixXd w;
  if (grad == nullptr) {
    Compute<false>(a, b, options, &w, nullptr, nullptr);
  } else {
    WritheJacobian jac;
    Compute<true>(a, b, options, &w, &jac, nullptr);
    grad->d_a0 = jac.pair.col(0).segment<3>(0);
    grad->d_a1 = jac.pair.col(0).segment<3>(3);
    grad->d_b0 = jac.pair.col(0).segment<3>(6);
    grad->d_b1 = jac.pair.col(0).segment<3>(9);
  }
  return w(0, 0);
}

void WritheMatrix(const Chain& a, const Chain& b, const WritheOptions& options, Eigen::MatrixXd* w,
                  WritheWorkspace* ws) {
  Compute<false>(a, b, options, w, nullptr, ws);
}

Eigen::MatrixXd WritheMatrix(const Chain& a, const Chain& b, const WritheOptions& options) {
  Eigen::MatrixXd w;
  Compute<false>(a, b, options, &w, nullptr, nullptr);
  return w;
}

void WritheMatrixWithJacobian(const Chain& a, const Chain& b, const WritheOptions& options,
                              Eigen::MatrixXd* w, WritheJacobian* jac, WritheWorkspace* ws) {
  Compute<true>(a, b, options, w, jac, ws);
}

double TotalWrithe(const Chain& a, const Chain& b, const WritheOptions& options) {
  WritheStreamOptions o;  // streamed: O(N_A + N_B) memory, one thread
  o.writhe = options;
  o.threads = 1;
  return StreamWritheSums(a, b, o).total;
}

double SelfWrithe(const Chain& a, const WritheOptions& options) {
  const Eigen::MatrixXd w = WritheMatrix(a, a, options);
  double sum = 0.0;
  for (Eigen::Index i = 0; i < w.rows(); ++i) {
    for (Eigen::Index j = i + 2; j < w.cols(); ++j) sum += w(i, j);
  }
  // For a closed chain (last point = first) the first and last segments share a point, so that
  // pair is degenerate and contributes 0 like every adjacent pair.
  return 2.0 * sum;
}

void WeightedWritheGradient(const WritheJacobian& jac, const Eigen::MatrixXd& weights,
                            Eigen::Matrix3Xd* grad_a, Eigen::Matrix3Xd* grad_b) {
  const bool ones = weights.size() == 0;
  if (!ones && (weights.rows() != jac.rows || weights.cols() != jac.cols)) {
    throw std::invalid_argument("WeightedWritheGradient: weights are " +
                                std::to_string(weights.rows()) + "x" +
                                std::to_string(weights.cols()) + ", expected " +
                                std::to_string(jac.rows) + "x" + std::to_string(jac.cols));
  }
  grad_a->setZero(3, jac.rows + 1);
  grad_b->setZero(3, jac.cols + 1);
  for (int i = 0; i < jac.rows; ++i) {
    for (int j = 0; j < jac.cols; ++j) {
      const double c = ones ? 1.0 : weights(i, j);
      const auto col = jac.pair.col(static_cast<Eigen::Index>(i) * jac.cols + j);
      grad_a->col(i) += c * col.segment<3>(0);
      grad_a->col(i + 1) += c * col.segment<3>(3);
      grad_b->col(j) += c * col.segment<3>(6);
      grad_b->col(j + 1) += c * col.segment<3>(9);
    }
  }
}

void ChainWritheJacobian(const WritheJacobian& jac, const Eigen::MatrixXd& da_dq,
                         const Eigen::MatrixXd& db_dq, Eigen::MatrixXd* out) {
  const bool has_a = da_dq.size() > 0, has_b = db_dq.size() > 0;
  if (!has_a && !has_b) throw std::invalid_argument("ChainWritheJacobian: no point Jacobians");
  const Eigen::Index nq = has_a ? da_dq.cols() : db_dq.cols();
  if (has_a && (da_dq.rows() != 3 * (jac.rows + 1))) {
    throw std::invalid_argument("ChainWritheJacobian: da_dq has " + std::to_string(da_dq.rows()) +
                                " rows, expected 3*N_A = " + std::to_string(3 * (jac.rows + 1)));
  }
  if (has_b && (db_dq.rows() != 3 * (jac.cols + 1) || (has_a && db_dq.cols() != nq))) {
    throw std::invalid_argument("ChainWritheJacobian: db_dq is " + std::to_string(db_dq.rows()) +
                                "x" + std::to_string(db_dq.cols()) + ", expected " +
                                std::to_string(3 * (jac.cols + 1)) + "x" + std::to_string(nq));
  }
  out->resize(static_cast<Eigen::Index>(jac.rows) * jac.cols, nq);
  for (int i = 0; i < jac.rows; ++i) {
    for (int j = 0; j < jac.cols; ++j) {
      const Eigen::Index k = static_cast<Eigen::Index>(i) * jac.cols + j;
      const auto g = jac.pair.col(k);
      auto row = out->row(k);
      row.setZero();
      if (has_a) {
        row.noalias() += g.segment<3>(0).transpose() * da_dq.middleRows<3>(3 * i);
        row.noalias() += g.segment<3>(3).transpose() * da_dq.middleRows<3>(3 * i + 3);
      }
      if (has_b) {
        row.noalias() += g.segment<3>(6).transpose() * db_dq.middleRows<3>(3 * j);
        row.noalias() += g.segment<3>(9).transpose() * db_dq.middleRows<3>(3 * j + 3);
      }
    }
  }
}

}  // namespace topology
