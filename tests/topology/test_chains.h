// Chain generators shared by the topology tests (known links, helices, seeded random chains).
#pragma once

#include <Eigen/Core>
#include <random>

#include "topology/polyline.h"

namespace topology::testing {

// Closed polygon with n segments (n+1 points, last = first) sampling f(t), t = 2πk/n.
template <typename F>
Chain ClosedCurve(F f, int n) {
  Chain c(3, n + 1);
  for (int k = 0; k < n; ++k) c.col(k) = f(6.283185307179586 * k / n);
  c.col(n) = c.col(0);
  return c;
}

// The Hopf link (docs/methods.md §2.1): A(t) = (cos t, sin t, 0), B(s) = (1 + cos s, 0, sin s).
Chain HopfA(int n);
Chain HopfB(int n);
// Component j ∈ {0, 1} of the (2, 2k) torus link (major radius R, minor r); linking number k.
Chain TorusLinkComponent(int k, int j, int n, double big_r = 2.0, double small_r = 0.7);
// Helix of `turns` turns, radius r, about the z axis, with `n` segments, z from −h/2 to h/2.
Chain Helix(double turns, double r, double h, int n);
// Random chain of n points, steps of length ~step, starting near `origin`.
Chain RandomChain(int n, double step, const Eigen::Vector3d& origin, std::mt19937* rng);

}  // namespace topology::testing
