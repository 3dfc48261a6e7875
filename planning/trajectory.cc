#include "planning/trajectory.h"

#include <cmath>
#include <stdexcept>

namespace planning {

double PathLength(const Trajectory& trajectory) {
  double length = 0.0;
  for (int t = 0; t + 1 < trajectory.num_points(); ++t) {
    length += (trajectory.q.col(t + 1) - trajectory.q.col(t)).norm();
  }
  return length;
}

Trajectory Densify(const Trajectory& trajectory, double resolution) {
  if (!(resolution > 0.0)) throw std::invalid_argument("Densify: resolution must be > 0");
  const int n = trajectory.num_dofs();
  const int points = trajectory.num_points();
  // Count the output size first, then fill.
  int total = points > 0 ? 1 : 0;
  for (int t = 0; t + 1 < points; ++t) {
    const double d = (trajectory.q.col(t + 1) - trajectory.q.col(t)).norm();
    total += std::max(1, static_cast<int>(std::ceil(d / resolution)));
  }
  Trajectory out;
  out.dt = 0.0;
  out.q.resize(n, total);
  if (points == 0) return out;
  int k = 0;
  out.q.col(k++) = trajectory.q.col(0);
  for (int t = 0; t + 1 < points; ++t) {
    const double d = (trajectory.q.col(t + 1) - trajectory.q.col(t)).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(d / resolution)));
    for (int i = 1; i <= steps; ++i) {
      const double s = static_cast<double>(i) / steps;
      out.q.col(k++) = (1.0 - s) * trajectory.q.col(t) + s * trajectory.q.col(t + 1);
    }
  }
  return out;
}

}  // namespace planning
