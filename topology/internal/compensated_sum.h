// Internal to the topology module: Neumaier's compensated summation, shared by the streamed
// totals (writhe_stream.cc) and the far-field sums (gauss_far_field.cc).
#pragma once

#include <cmath>

namespace topology::internal {

// |result − exact| ≤ 2u Σ|x_k| + O(n u²) Σ|x_k| (u = 2⁻⁵³).
struct CompensatedSum {
  double sum = 0.0, comp = 0.0;
  void Add(double x) {
    const double t = sum + x;
    comp += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double Value() const { return sum + comp; }
};

}  // namespace topology::internal
