#include "planning/motion/trajectory.h"

#include "base/numbers.h"

#include <algorithm>
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

std::int64_t EdgeSteps(double distance, double resolution) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("edge resolution must be a finite number > 0, got " +
                                std::to_string(resolution));
  }
  if (!std::isfinite(distance)) throw std::invalid_argument("edge length is not finite");
  const double steps = std::ceil(distance / resolution);
  if (steps > static_cast<double>(kMaxEdgeSteps)) {
    throw std::invalid_argument("edge resolution " + std::to_string(resolution) +
                                " is too fine: an edge of length " + base::FormatShortest(distance) +
                                " would need " + std::to_string(steps) + " states (limit " +
                                std::to_string(kMaxEdgeSteps) + ")");
  }
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(steps));
}

Trajectory Densify(const Trajectory& trajectory, double resolution) {
  if (!(resolution > 0.0)) throw std::invalid_argument("Densify: resolution must be > 0");
  const int n = trajectory.num_dofs();
  const int points = trajectory.num_points();
  // Count the output size first, then fill.
  std::int64_t total = points > 0 ? 1 : 0;
  for (int t = 0; t + 1 < points; ++t) {
    total += EdgeSteps((trajectory.q.col(t + 1) - trajectory.q.col(t)).norm(), resolution);
    if (total > kMaxEdgeSteps) {
      throw std::invalid_argument("Densify: resolution " + std::to_string(resolution) +
                                  " would give more than " + std::to_string(kMaxEdgeSteps) +
                                  " waypoints");
    }
  }
  Trajectory out;
  out.dt = 0.0;
  out.q.resize(n, static_cast<Eigen::Index>(total));
  if (points == 0) return out;
  Eigen::Index k = 0;
  out.q.col(k++) = trajectory.q.col(0);
  for (int t = 0; t + 1 < points; ++t) {
    const std::int64_t steps =
        EdgeSteps((trajectory.q.col(t + 1) - trajectory.q.col(t)).norm(), resolution);
    for (std::int64_t i = 1; i <= steps; ++i) {
      const double s = static_cast<double>(i) / static_cast<double>(steps);
      out.q.col(k++) = (1.0 - s) * trajectory.q.col(t) + s * trajectory.q.col(t + 1);
    }
  }
  return out;
}

}  // namespace planning
