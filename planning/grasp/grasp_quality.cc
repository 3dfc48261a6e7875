#include "planning/grasp/grasp_quality.h"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

extern "C" {
#include <libqhull_r/qhull_ra.h>

#include <numbers>
}

namespace planning {
namespace {

// Tangent t1 ⊥ n (unit), built from the coordinate axis least aligned with n.
Eigen::Vector3d Tangent(const Eigen::Vector3d& n) {
  int axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  return n.cross(Eigen::Vector3d::Unit(axis)).normalized();
}

// Smallest distance from the origin to a facet hyperplane of conv(columns of w), or 0 when the
// origin is not strictly inside. Throws std::runtime_error for an unexpected qhull failure.
double InscribedRadius(const Eigen::Matrix<double, 6, Eigen::Dynamic>& w) {
  std::vector<coordT> points(w.data(), w.data() + w.size());  // column-major = point after point
  char* buffer = nullptr;
  size_t size = 0;
  FILE* err = open_memstream(&buffer, &size);
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, err);
  char flags[] = "qhull Qt";
  const int exit_code =
      qh_new_qhull(qh, 6, static_cast<int>(w.cols()), points.data(), False, flags, nullptr, err);
  double radius = std::numeric_limits<double>::infinity();
  if (exit_code == 0) {
    facetT* facet = nullptr;
    FORALLfacets {
      // Outward unit normal, hyperplane normal·x + offset = 0; inside points give ≤ 0.
      radius = std::min(radius, -facet->offset);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(err);
  const std::string message(buffer ? buffer : "");
  std::free(buffer);
  if (exit_code == qh_ERRsingular || exit_code == qh_ERRprec) return 0.0;  // flat hull
  if (exit_code != 0) throw std::runtime_error("EpsilonQuality: qhull failed: " + message);
  return std::isfinite(radius) ? std::max(0.0, radius) : 0.0;
}

}  // namespace

Eigen::Matrix<double, 6, Eigen::Dynamic> PrimitiveWrenches(
    const std::vector<GraspContact>& contacts, const Eigen::Vector3d& centre, double mu,
    const EpsilonOptions& options) {
  if (!(mu >= 0) || !std::isfinite(mu)) {
    throw std::invalid_argument("EpsilonQuality: mu must be a finite number >= 0");
  }
  if (options.friction_edges < 3) {
    throw std::invalid_argument("EpsilonQuality: friction_edges must be >= 3");
  }
  if (!(options.radius_of_gyration > 0) || !std::isfinite(options.radius_of_gyration)) {
    throw std::invalid_argument("EpsilonQuality: radius_of_gyration must be finite and > 0");
  }
  if (!centre.allFinite()) throw std::invalid_argument("EpsilonQuality: non-finite centre");
  const int m = options.friction_edges;
  Eigen::Matrix<double, 6, Eigen::Dynamic> w(6, static_cast<Eigen::Index>(contacts.size()) * m);
  for (size_t i = 0; i < contacts.size(); ++i) {
    const GraspContact& c = contacts[i];
    if (!c.position.allFinite() || !c.normal.allFinite() || c.normal.norm() < 1e-12) {
      throw std::invalid_argument("EpsilonQuality: contact " + std::to_string(i) +
                                  ": non-finite point or zero normal");
    }
    const Eigen::Vector3d n = c.normal.normalized();
    const Eigen::Vector3d t1 = Tangent(n);
    const Eigen::Vector3d t2 = n.cross(t1);
    const Eigen::Vector3d r = c.position - centre;
    for (int k = 0; k < m; ++k) {
      const double theta = 2.0 * std::numbers::pi * k / m;
      const Eigen::Vector3d f = n + mu * (std::cos(theta) * t1 + std::sin(theta) * t2);
      const Eigen::Index col = static_cast<Eigen::Index>(i) * m + k;
      w.col(col).head<3>() = f;
      w.col(col).tail<3>() = r.cross(f) / options.radius_of_gyration;
    }
  }
  return w;
}

double EpsilonQuality(const std::vector<GraspContact>& contacts, const Eigen::Vector3d& centre,
                      double mu, const EpsilonOptions& options) {
  const Eigen::Matrix<double, 6, Eigen::Dynamic> w =
      PrimitiveWrenches(contacts, centre, mu, options);
  if (contacts.size() < 2) return 0.0;
  // The origin can only be strictly inside a hull that spans ℝ⁶.
  Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 6, Eigen::Dynamic>> qr(w);
  qr.setThreshold(1e-9);
  if (qr.rank() < 6) return 0.0;
  return InscribedRadius(w);
}

Eigen::Vector2d WilsonInterval(int successes, int trials, double z) {
  if (trials < 1 || successes < 0 || successes > trials || !(z > 0) || !std::isfinite(z)) {
    throw std::invalid_argument(
        "WilsonInterval: need 0 <= successes <= trials, trials >= 1, z > 0");
  }
  const double n = trials;
  const double p = successes / n;
  const double z2 = z * z;
  const double denom = 1.0 + z2 / n;
  const double centre = (p + z2 / (2.0 * n)) / denom;
  const double half = z / denom * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n));
  return Eigen::Vector2d(std::max(0.0, centre - half), std::min(1.0, centre + half));
}

namespace {

// Ranks 1..n of v, ties given the mean of the ranks they span.
std::vector<double> AverageRanks(const std::vector<double>& v) {
  std::vector<size_t> order(v.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<double> rank(v.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double mean = 0.5 * static_cast<double>(i + j) + 1.0;
    for (size_t k = i; k <= j; ++k) rank[order[k]] = mean;
    i = j + 1;
  }
  return rank;
}

}  // namespace

std::optional<double> SpearmanCorrelation(const std::vector<double>& x,
                                          const std::vector<double>& y) {
  if (x.size() != y.size()) {
    throw std::invalid_argument("SpearmanCorrelation: x has " + std::to_string(x.size()) +
                                " values, y " + std::to_string(y.size()));
  }
  for (size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw std::invalid_argument("SpearmanCorrelation: non-finite value at index " +
                                  std::to_string(i));
    }
  }
  if (x.size() < 2) return std::nullopt;
  const std::vector<double> rx = AverageRanks(x), ry = AverageRanks(y);
  const double mean = 0.5 * static_cast<double>(x.size() + 1);  // mean rank, ties included
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (rx[i] - mean) * (ry[i] - mean);
    sxx += (rx[i] - mean) * (rx[i] - mean);
    syy += (ry[i] - mean) * (ry[i] - mean);
  }
  if (sxx <= 0.0 || syy <= 0.0) return std::nullopt;
  return sxy / std::sqrt(sxx * syy);
}

}  // namespace planning
