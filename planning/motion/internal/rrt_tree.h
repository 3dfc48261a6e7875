// The tree operations shared by the project's RRTs (rrt.cc: one goal state; goal_region.cc: a
// goal region): the counted validity checker, the edge rule, nearest neighbour, uniform sampling,
// steering and path extraction. Private to planning/motion.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "planning/motion/rrt.h"
#include "planning/motion/trajectory.h"

namespace planning::internal {

enum class EdgeResult { kValid, kInvalid, kBudget };

// Counts validity calls and enforces the budget: count = calls made, exhausted() once count >=
// max_checks.
struct Checker {
  const ValidityFn& valid;
  std::int64_t max_checks;
  std::int64_t count = 0;

  bool exhausted() const { return count >= max_checks; }
  bool operator()(const Eigen::VectorXd& q) {
    ++count;
    return valid(q);
  }
};

// Throws std::invalid_argument unless start, lower and upper (and `goal`, when given) have one
// non-zero size n, are finite and lower <= upper. `who` names the planner in the message.
void CheckBox(const char* who, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
              const Eigen::VectorXd& start, const Eigen::VectorXd* goal);

// The per-run constants of the edge rule: range = options.range (<= 0: 0.2 D), resolution =
// options.resolution (<= 0: 0.01 D; 1 for D = 0), D = ‖upper − lower‖. Throws
// std::invalid_argument when they are not finite or an edge of length range needs more than
// kMaxEdgeSteps states.
void RangeAndResolution(const RrtOptions& options, const Eigen::VectorXd& lower,
                        const Eigen::VectorXd& upper, double* range, double* resolution);

// Edge from → to at `resolution`: the end state first, then the ⌈d/res⌉ − 1 interior states
// (1 − s)·from + s·to, s = i/⌈d/res⌉, in order. kBudget when the budget runs out before a state
// is checked; *tmp (size n) is scratch.
EdgeResult CheckEdge(const Eigen::VectorXd& from, const Eigen::VectorXd& to, double resolution,
                     Checker* check, Eigen::VectorXd* tmp);

// argmin_i ‖tree[i].q − q‖ (the first on ties); tree non-empty.
int Nearest(const std::vector<RrtNode>& tree, const Eigen::VectorXd& q);

// q_i = lower_i + u_i (upper_i − lower_i), u_i = base::UniformUnit(rng), i = 0..n−1 in order.
void SampleUniform(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, std::mt19937* rng,
                   Eigen::VectorXd* q);

// q_new = q_target if ‖q_target − q_near‖ <= range, else q_near + range·(q_target − q_near)/d.
void Steer(const Eigen::VectorXd& q_near, const Eigen::VectorXd& q_target, double range,
           Eigen::VectorXd* q_new);

// Appends the node indices root → `index` (reverse: index → root) of `tree` to *out (a forest:
// the branch ends at the root of `index`, parent −1).
void AppendBranch(const std::vector<RrtNode>& tree, int index, bool reverse, std::vector<int>* out);

// The path of the nodes start_tree[root .. start_end] then goal_tree[goal_end .. root] (goal_tree
// null or goal_end < 0: the start-tree branch only), one column per node.
Trajectory BranchPath(const std::vector<RrtNode>& start_tree, int start_end,
                      const std::vector<RrtNode>* goal_tree, int goal_end);

}  // namespace planning::internal
