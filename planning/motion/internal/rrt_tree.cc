#include "planning/motion/internal/rrt_tree.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "base/random.h"
#include "base/str_cat.h"

namespace planning::internal {

void CheckBox(const char* who, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
              const Eigen::VectorXd& start, const Eigen::VectorXd* goal) {
  const Eigen::Index n = start.size();
  const Eigen::Index goal_n = goal != nullptr ? goal->size() : n;
  if (n == 0 || goal_n != n || lower.size() != n || upper.size() != n) {
    throw std::invalid_argument(
        base::StrCat(who, ": start, goal, lower, upper must have the same non-zero size (",
                     std::to_string(n), ", ", std::to_string(goal_n), ", ",
                     std::to_string(lower.size()), ", ", std::to_string(upper.size()), ")"));
  }
  if (!start.allFinite() || (goal != nullptr && !goal->allFinite()) || !lower.allFinite() ||
      !upper.allFinite()) {
    throw std::invalid_argument(base::StrCat(who, ": non-finite start, goal or bounds"));
  }
  if ((upper - lower).minCoeff() < 0.0) {
    throw std::invalid_argument(base::StrCat(who, ": a lower bound exceeds its upper bound"));
  }
}

void RangeAndResolution(const RrtOptions& options, const Eigen::VectorXd& lower,
                        const Eigen::VectorXd& upper, double* range, double* resolution) {
  const double diag = (upper - lower).norm();
  *range = options.range > 0 ? options.range : 0.2 * diag;
  // A zero-volume box (diag = 0) has only zero-length edges: any resolution checks them.
  *resolution = options.resolution > 0 ? options.resolution : (diag > 0 ? 0.01 * diag : 1.0);
  if (!std::isfinite(*range) || !std::isfinite(*resolution)) {
    throw std::invalid_argument("RRT: range and resolution must be finite");
  }
  EdgeSteps(*range, *resolution);  // the longest edge must be checkable (throws)
}

EdgeResult CheckEdge(const Eigen::VectorXd& from, const Eigen::VectorXd& to, double resolution,
                     Checker* check, Eigen::VectorXd* tmp) {
  if (check->exhausted()) return EdgeResult::kBudget;
  if (!(*check)(to)) return EdgeResult::kInvalid;
  const std::int64_t steps = EdgeSteps((to - from).norm(), resolution);
  for (std::int64_t i = 1; i < steps; ++i) {
    if (check->exhausted()) return EdgeResult::kBudget;
    const double s = static_cast<double>(i) / static_cast<double>(steps);
    tmp->noalias() = (1.0 - s) * from + s * to;
    if (!(*check)(*tmp)) return EdgeResult::kInvalid;
  }
  return EdgeResult::kValid;
}

int Nearest(const std::vector<RrtNode>& tree, const Eigen::VectorXd& q) {
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(tree.size()); ++i) {
    const double d = (tree[i].q - q).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

void SampleUniform(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, std::mt19937* rng,
                   Eigen::VectorXd* q) {
  for (Eigen::Index i = 0; i < q->size(); ++i) {
    (*q)[i] = lower[i] + base::UniformUnit(rng) * (upper[i] - lower[i]);
  }
}

void Steer(const Eigen::VectorXd& q_near, const Eigen::VectorXd& q_target, double range,
           Eigen::VectorXd* q_new) {
  const double d = (q_target - q_near).norm();
  if (d <= range) {
    *q_new = q_target;
  } else {
    q_new->noalias() = q_near + (range / d) * (q_target - q_near);
  }
}

void AppendBranch(const std::vector<RrtNode>& tree, int index, bool reverse,
                  std::vector<int>* out) {
  std::vector<int> branch;
  for (int i = index; i >= 0; i = tree[i].parent) branch.push_back(i);
  if (!reverse) {
    out->insert(out->end(), branch.rbegin(), branch.rend());
  } else {
    out->insert(out->end(), branch.begin(), branch.end());
  }
}

Trajectory BranchPath(const std::vector<RrtNode>& start_tree, int start_end,
                      const std::vector<RrtNode>* goal_tree, int goal_end) {
  std::vector<int> from_start, from_goal;
  AppendBranch(start_tree, start_end, false, &from_start);
  if (goal_tree != nullptr && goal_end >= 0) AppendBranch(*goal_tree, goal_end, true, &from_goal);
  Trajectory path;
  path.q.resize(start_tree[start_end].q.size(),
                static_cast<Eigen::Index>(from_start.size() + from_goal.size()));
  Eigen::Index col = 0;
  for (int i : from_start) path.q.col(col++) = start_tree[i].q;
  for (int i : from_goal) path.q.col(col++) = (*goal_tree)[i].q;
  return path;
}

}  // namespace planning::internal
