#include "tests/topology/test_chains.h"

#include <cmath>

namespace topology::testing {

Chain HopfA(int n) {
  return ClosedCurve([](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), 0); }, n);
}
Chain HopfB(int n) {
  return ClosedCurve([](double s) { return Eigen::Vector3d(1 + std::cos(s), 0, std::sin(s)); }, n);
}

Chain TorusLinkComponent(int k, int j, int n, double big_r, double small_r) {
  return ClosedCurve(
      [=](double t) {
        const double psi = k * t + j * M_PI;
        return Eigen::Vector3d((big_r + small_r * std::cos(psi)) * std::cos(t),
                               (big_r + small_r * std::cos(psi)) * std::sin(t),
                               small_r * std::sin(psi));
      },
      n);
}

Chain Helix(double turns, double r, double h, int n) {
  Chain c(3, n + 1);
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    const double t = 2 * M_PI * turns * s;
    c.col(k) << r * std::cos(t), r * std::sin(t), -h / 2 + h * s;
  }
  return c;
}

Chain RandomChain(int n, double step, const Eigen::Vector3d& origin, std::mt19937* rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Chain c(3, n);
  c.col(0) = origin;
  for (int k = 1; k < n; ++k) {
    Eigen::Vector3d d(g(*rng), g(*rng), g(*rng));
    c.col(k) = c.col(k - 1) + step * d.normalized();
  }
  return c;
}

}  // namespace topology::testing
