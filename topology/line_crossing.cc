#include "topology/line_crossing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace topology {
namespace {

// f_j(s) of every segment of `p` (size N − 1) about the line through a along unit d.
void SegmentSides(const Chain& p, const Eigen::Vector3d& a, const Eigen::Vector3d& d,
                  Eigen::VectorXd* f) {
  f->resize(p.cols() - 1);
  for (Eigen::Index j = 0; j + 1 < p.cols(); ++j) {
    const Eigen::Vector3d u0 = p.col(j) - a, u1 = p.col(j + 1) - a;
    (*f)[j] = d.dot(u0.cross(u1));  // the components along d drop out of d·(u0 × u1)
  }
}

void Evaluate(const ChainMotion& motion, double s, Eigen::Index n, Chain* p) {
  motion(s, p);
  if (p->cols() != n) {
    throw std::invalid_argument("LocateLineCrossings: the chain's point count changes with s");
  }
  if (!p->allFinite()) throw std::invalid_argument("LocateLineCrossings: non-finite chain point");
}

int Sign(double x) { return (x > 0.0) - (x < 0.0); }

}  // namespace

std::vector<LineCrossing> LocateLineCrossings(const ChainMotion& motion, const Eigen::Vector3d& a,
                                              const Eigen::Vector3d& b, double s_tolerance) {
  const Eigen::Vector3d ab = b - a;
  if (!a.allFinite() || !b.allFinite() || ab.squaredNorm() == 0.0) {
    throw std::invalid_argument("LocateLineCrossings: the line needs two distinct finite points");
  }
  if (!(s_tolerance > 0.0 && s_tolerance < 1.0)) {
    throw std::invalid_argument("LocateLineCrossings: s_tolerance must be in (0, 1)");
  }
  const Eigen::Vector3d d = ab.normalized();
  Chain p0, p1, p;
  motion(0.0, &p0);
  if (p0.cols() < 2) throw std::invalid_argument("LocateLineCrossings: chain needs 2 points");
  Evaluate(motion, 1.0, p0.cols(), &p1);
  if (!p0.allFinite()) throw std::invalid_argument("LocateLineCrossings: non-finite chain point");
  Eigen::VectorXd f0, f1, f;
  SegmentSides(p0, a, d, &f0);
  SegmentSides(p1, a, d, &f1);
  std::vector<LineCrossing> out;
  for (Eigen::Index j = 0; j < f0.size(); ++j) {
    const int side0 = Sign(f0[j]);
    if (side0 == Sign(f1[j])) continue;
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 64 && hi - lo > s_tolerance; ++it) {
      const double mid = 0.5 * (lo + hi);
      Evaluate(motion, mid, p0.cols(), &p);
      SegmentSides(p, a, d, &f);
      (Sign(f[j]) == side0 ? lo : hi) = mid;
    }
    const double s = 0.5 * (lo + hi);
    Evaluate(motion, s, p0.cols(), &p);
    const Eigen::Vector3d u0 = (p.col(j) - a) - d * d.dot(p.col(j) - a);
    const Eigen::Vector3d u1 = (p.col(j + 1) - a) - d * d.dot(p.col(j + 1) - a);
    if (u0.dot(u1) >= 0.0) continue;  // the segment's extension, not the segment, meets the line
    const double r0 = u0.norm(), r1 = u1.norm();
    const double lambda = r0 / (r0 + r1);
    const Eigen::Vector3d x = p.col(j) + lambda * (p.col(j + 1) - p.col(j));
    out.push_back({static_cast<int>(j), s, ab.dot(x - a) / ab.squaredNorm()});
  }
  std::sort(out.begin(), out.end(),
            [](const LineCrossing& x, const LineCrossing& y) { return x.s < y.s; });
  return out;
}

double LineDistanceBeyondEnds(const Chain& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double length = (b - a).norm();
  if (!(length > 0.0)) throw std::invalid_argument("LineDistanceBeyondEnds: a = b");
  if (p.cols() < 2) throw std::invalid_argument("LineDistanceBeyondEnds: fewer than 2 points");
  const Eigen::Vector3d d = (b - a) / length;
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index j = 0; j + 1 < p.cols(); ++j) {
    const Eigen::Vector3d u = p.col(j) - a, e = p.col(j + 1) - p.col(j);
    const double t0 = d.dot(u), te = d.dot(e);               // t(λ) = t0 + λ te
    const Eigen::Vector3d up = u - t0 * d, ep = e - te * d;  // parts perpendicular to the line
    const double ee = ep.squaredNorm();
    // [lo, hi]: the λ of [0, 1] with t(λ) < bound (below) or t(λ) > bound (!below); lo > hi if
    // none.
    const auto beyond = [&](double bound, bool below, double* lo, double* hi) {
      *lo = 0.0;
      *hi = 1.0;
      if (te == 0.0) {
        if (below ? !(t0 < bound) : !(t0 > bound)) *lo = 2.0;
        return;
      }
      const double cut = (bound - t0) / te;
      if ((te > 0.0) == below) {
        *hi = std::min(1.0, cut);
      } else {
        *lo = std::max(0.0, cut);
      }
    };
    for (const bool below : {true, false}) {
      double lo = 0.0, hi = 0.0;
      beyond(below ? 0.0 : length, below, &lo, &hi);
      if (lo > hi) continue;
      const double lambda = ee > 0.0 ? std::clamp(-up.dot(ep) / ee, lo, hi) : lo;
      best = std::min(best, (up + lambda * ep).norm());
    }
  }
  return best;
}

}  // namespace topology
