#include "topology/linking_crossings.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "topology/internal/writhe_rows.h"

namespace topology {
namespace {

constexpr double kU = 0x1p-53;  // unit roundoff of double
// Shewchuk (1997): the forward-error bounds of the plain floating-point determinants, valid
// without underflow; kUnderflow covers the absolute error of products in the subnormal range.
constexpr double kSideBound = 10.0 * kU;
constexpr double kOrient3Bound = (7.0 + 56.0 * kU) * kU;
constexpr double kUnderflow = 1e-300;

// Which side of the plane through p and q spanned by q − p and d the point x lies on: the sign of
// det[q − p; d; x − p], +1, −1, or 0 when |det| is within its error bound. Seen along d, that is
// the side of the shadow of line pq the shadow of x falls on. The bound: the differences, the
// products, the 2×2 minors, the products with d and the sum of three add ≤ 7u + O(u²) relative
// to the permanent; 10u is used.
inline int Side(const double* p, const double* q, const Eigen::Vector3d& d, const double* x) {
  const double ax = q[0] - p[0], ay = q[1] - p[1], az = q[2] - p[2];
  const double cx = x[0] - p[0], cy = x[1] - p[1], cz = x[2] - p[2];
  const double m0l = cy * az, m0r = cz * ay, m1l = cz * ax, m1r = cx * az, m2l = cx * ay,
               m2r = cy * ax;
  const double det = d[0] * (m0l - m0r) + d[1] * (m1l - m1r) + d[2] * (m2l - m2r);
  const double permanent = std::abs(d[0]) * (std::abs(m0l) + std::abs(m0r)) +
                           std::abs(d[1]) * (std::abs(m1l) + std::abs(m1r)) +
                           std::abs(d[2]) * (std::abs(m2l) + std::abs(m2r));
  const double bound = kSideBound * permanent + kUnderflow;
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

// Sign of det[a − d; b − d; c − d] (points of 3 doubles): +1, −1, or 0 within its error bound.
inline int Orient3(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  const double bound = kOrient3Bound * permanent + kUnderflow;
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

// A segment's shadow: the box of its endpoints' coordinates (u, v) in the projection plane,
// widened by the rounding of u and v, so that two shadows that meet have boxes that meet; the
// endpoints themselves are the input points p, p + 3 (the chain's storage).
struct Shadow {
  const double* p;
  double umin, umax, vmin, vmax;
};

void Shadows(const Chain& c, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
             std::vector<Shadow>* out) {
  const int n = static_cast<int>(c.cols()) - 1;
  out->resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    Shadow& s = (*out)[static_cast<size_t>(i)];
    s.p = c.col(i).data();
    const Eigen::Vector3d a = c.col(i), b = c.col(i + 1);
    const double ua = e1.dot(a), ub = e1.dot(b), va = e2.dot(a), vb = e2.dot(b);
    const double mag = a.cwiseAbs().sum() + b.cwiseAbs().sum();
    // Rounding of u, v (≤ 3u mag) plus e1, e2 off orthogonal to d by a few u: two points that
    // are exact shadows of each other (x − y ∥ d, |x − y| ≤ mag_a + mag_b) get (u, v) within
    // well under 64u (mag_a + mag_b) of each other; each box takes its half.
    const double w = 64.0 * kU * mag + kUnderflow;
    s.umin = std::min(ua, ub) - w, s.umax = std::max(ua, ub) + w;
    s.vmin = std::min(va, vb) - w, s.vmax = std::max(va, vb) + w;
  }
}

// Whether the shadows along d of segments a and b cross at one interior point: +1 yes, 0 no, −1
// undecided (a decision within its error bound: an endpoint on the other shadow, collinear
// shadows).
inline int ShadowsCross(const Shadow& a, const Shadow& b, const Eigen::Vector3d& d) {
  if (a.umax < b.umin || b.umax < a.umin || a.vmax < b.vmin || b.vmax < a.vmin) return 0;
  const double *a0 = a.p, *a1 = a.p + 3, *b0 = b.p, *b1 = b.p + 3;
  const int o1 = Side(a0, a1, d, b0);
  const int o2 = Side(a0, a1, d, b1);
  if (o1 != 0 && o1 == o2) return 0;  // b on one side of a's shadow line
  const int o3 = Side(b0, b1, d, a0);
  const int o4 = Side(b0, b1, d, a1);
  if (o3 != 0 && o3 == o4) return 0;  // a on one side of b's shadow line
  if (o1 == 0 || o2 == 0 || o3 == 0 || o4 == 0) return -1;
  return 1;  // o1 = −o2 and o3 = −o4, all certain
}

// Uniform grid over the boxes of B's shadows, each shadow listed in every cell its box meets
// (compressed rows). Cell coordinates are a monotone function of u and v, so two boxes that
// overlap share at least one cell.
class ShadowGrid {
 public:
  explicit ShadowGrid(const std::vector<Shadow>& b) {
    umin_ = vmin_ = std::numeric_limits<double>::infinity();
    double umax = -umin_, vmax = -vmin_, extent = 0.0;
    for (const Shadow& s : b) {
      umin_ = std::min(umin_, s.umin), umax = std::max(umax, s.umax);
      vmin_ = std::min(vmin_, s.vmin), vmax = std::max(vmax, s.vmax);
      extent += std::max(s.umax - s.umin, s.vmax - s.vmin);
    }
    const double n = static_cast<double>(b.size());
    const double width = umax - umin_, height = vmax - vmin_;
    // Cells about one mean shadow across, at most ~4 per shadow and 4096 per side.
    h_ = extent / n;
    if (!(h_ > 0.0) || !std::isfinite(h_)) h_ = std::max({width, height, 1.0});
    for (;;) {
      nu_ = static_cast<int>(std::min(4095.0, width / h_)) + 1;
      nv_ = static_cast<int>(std::min(4095.0, height / h_)) + 1;
      if (static_cast<double>(nu_) * nv_ <= 4.0 * n + 64.0) break;
      h_ *= 1.5;
    }
    start_.assign(static_cast<size_t>(nu_) * nv_ + 1, 0);
    for (const Shadow& s : b) {
      ForCells(s, [&](size_t cell) { ++start_[cell + 1]; });
    }
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(static_cast<size_t>(start_.back()));
    std::vector<long long> fill(start_.begin(), start_.end() - 1);
    for (int j = 0; j < static_cast<int>(b.size()); ++j) {
      ForCells(b[static_cast<size_t>(j)],
               [&](size_t cell) { items_[static_cast<size_t>(fill[cell]++)] = j; });
    }
  }

  // Calls f(cell) for every cell the box of s meets.
  template <typename F>
  void ForCells(const Shadow& s, F&& f) const {
    const int u0 = Cell(s.umin, umin_, nu_), u1 = Cell(s.umax, umin_, nu_);
    const int v0 = Cell(s.vmin, vmin_, nv_), v1 = Cell(s.vmax, vmin_, nv_);
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) f(static_cast<size_t>(v) * nu_ + u);
    }
  }
  const int* begin(size_t cell) const { return items_.data() + start_[cell]; }
  const int* end(size_t cell) const { return items_.data() + start_[cell + 1]; }

 private:
  int Cell(double x, double lo, int n) const {
    const double c = (x - lo) / h_;  // monotone in x
    return c <= 0.0 ? 0 : c >= n - 1 ? n - 1 : static_cast<int>(c);
  }

  double umin_, vmin_, h_;
  int nu_ = 1, nv_ = 1;
  std::vector<long long> start_;
  std::vector<int> items_;
};

// Σ ε over the crossings of the projection along d; false when d is degenerate for these
// chains or some crossing's sign is undecided.
bool CountCrossings(const Chain& a, const Chain& b, const Eigen::Vector3d& d, long long* sum,
                    long long* count) {
  const Eigen::Vector3d e1 = d.unitOrthogonal(), e2 = d.normalized().cross(e1);
  std::vector<Shadow> sa, sb;
  Shadows(a, e1, e2, &sa);
  Shadows(b, e1, e2, &sb);
  const ShadowGrid grid(sb);
  std::vector<int> seen(sb.size(), -1);
  *sum = 0;
  *count = 0;
  for (int i = 0; i < static_cast<int>(sa.size()); ++i) {
    const Shadow& s = sa[static_cast<size_t>(i)];
    bool ok = true;
    grid.ForCells(s, [&](size_t cell) {
      for (const int* p = grid.begin(cell); ok && p != grid.end(cell); ++p) {
        const int j = *p;
        if (seen[static_cast<size_t>(j)] == i) continue;
        seen[static_cast<size_t>(j)] = i;
        const int cross = ShadowsCross(s, sb[static_cast<size_t>(j)], d);
        if (cross == 0) continue;
        if (cross < 0) {
          ok = false;
          return;
        }
        // ε = sign((a1 − a0) × (b1 − b0) · (a0 − b0)) = sign det[a0 − b0; a1 − b0; b1 − b0].
        const int e =
            Orient3(a.col(i).data(), a.col(i + 1).data(), b.col(j + 1).data(), b.col(j).data());
        if (e == 0) {
          ok = false;
          return;
        }
        *sum += e;
        ++*count;
      }
    });
    if (!ok) return false;
  }
  return *sum % 2 == 0;  // two closed shadows cross an even number of times
}

// Projection directions tried in turn: generic (no two components in a simple ratio), so that
// symmetric inputs (points on coordinate planes, equal azimuths) do not project degenerately.
const Eigen::Vector3d kDirections[] = {
    {0.2718281828459045, 0.3141592653589793, 0.9092974268256817},
    {0.8414709848078965, -0.5403023058681398, 0.1411200080598672},
    {-0.4161468365471424, 0.7568024953079282, 0.6569865987187891}};

}  // namespace

LinkingResult CrossingLinkingNumber(const Chain& a, const Chain& b) {
  Chain snapped_a, snapped_b;
  const Chain& ca = internal::CheckClosedSnapped(a, "A", &snapped_a);
  const Chain& cb = internal::CheckClosedSnapped(b, "B", &snapped_b);
  LinkingResult r;
  r.method = LinkingMethod::kCrossings;
  r.gauss_integral = std::numeric_limits<double>::quiet_NaN();
  r.segments_a = static_cast<int>(ca.cols()) - 1;
  r.segments_b = static_cast<int>(cb.cols()) - 1;
  for (const Eigen::Vector3d& d : kDirections) {
    long long sum = 0, count = 0;
    if (!CountCrossings(ca, cb, d, &sum, &count)) continue;
    r.linking_number = sum / 2;
    r.crossings = count;
    r.projection = d;
    r.status = LinkingStatus::kCertified;
    return r;
  }
  r.status = LinkingStatus::kUncertain;
  return r;
}

LinkingResult LinkingNumberAuto(const Chain& a, const Chain& b, LinkingMethod method,
                                const WritheStreamOptions& stream) {
  if (method == LinkingMethod::kAuto && stream.far_field_tol > 0.0) method = LinkingMethod::kGauss;
  if (method != LinkingMethod::kGauss) {
    LinkingResult r = CrossingLinkingNumber(a, b);
    if (r.status == LinkingStatus::kCertified || method == LinkingMethod::kCrossings) return r;
  }
  return LinkingNumber(a, b, stream);
}

}  // namespace topology
