// Sampling-based baselines of thesis Fig. 4.5: uni-directional RRT with goal bias and a
// bi-directional RRT, both on a box-bounded joint space with a user validity checker.
//
// Shape follows OMPL (Sucan et al. 2012): the planner sees the world only through
// `ValidityFn(q) -> bool`; every call is one "collision check" and is counted. Edges are checked
// at a fixed resolution: an edge of length d is valid when its end state and the ⌈d/res⌉ − 1
// interior states (at i/⌈d/res⌉, i = 1..) are valid, the end state checked first. A run stops as
// failed when the number of checks reaches `max_checks` (status kBudgetExhausted). No smoothing.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "planning/trajectory.h"

namespace planning {

// q -> true when q is collision-free (and otherwise admissible). Called once per checked state.
using ValidityFn = std::function<bool(const Eigen::VectorXd& q)>;

// Joint-space box [lower, upper] (each num_dofs), start q_0 and goal q_T (from the final-pose
// estimate in the thesis set-up).
struct RrtProblem {
  Eigen::VectorXd lower, upper;
  Eigen::VectorXd start, goal;
};

struct RrtOptions {
  // Maximum extension length (joint-space Euclidean, radians). <= 0 means 0.2 × the diagonal of
  // the joint box (OMPL's default range).
  double range = 0.0;
  // Edge-check resolution (same unit). <= 0 means 0.01 × the box diagonal (OMPL's default
  // longest-valid-segment fraction).
  double resolution = 0.0;
  // Uni-RRT: probability of extending toward q_T instead of a uniform sample (thesis: 0.1).
  // Bi-RRT: probability of extending toward a random node of the other tree (thesis: 0.1).
  double goal_bias = 0.1;
  // Budget of validity checks; reaching it ends the run with kBudgetExhausted.
  std::int64_t max_checks = 100000;
  // Hard cap on loop iterations (guards against a checker that always fails before the budget).
  std::int64_t max_iterations = 10000000;
};

struct RrtResult {
  SolveStatus status = SolveStatus::kBudgetExhausted;
  Trajectory path;              // start .. goal waypoints (tree nodes), empty on failure
  std::int64_t checks = 0;      // validity-function calls made by this run
  std::int64_t iterations = 0;  // sampling iterations
  int tree_size = 0;            // total number of nodes in all trees
};

// One tree node: configuration and the index of its parent (−1 for the root).
struct RrtNode {
  Eigen::VectorXd q;
  int parent = -1;
};

// Uni-directional RRT (LaValle 1998) from start toward goal with goal bias: each iteration draws
// q_rand uniformly in the box (or q_rand = goal with probability goal_bias), extends the nearest
// node by at most `range`, and adds the new node if the edge is valid. Succeeds when an added node
// is the goal itself. Checks the start state first (invalid start or goal → kInvalidInput).
// Throws std::invalid_argument on inconsistent sizes, non-finite values or lower > upper.
// Deterministic for a given *rng state.
RrtResult PlanRrt(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                  std::mt19937* rng);

// Bi-directional RRT: trees rooted at start and goal grow alternately. The growing tree extends
// toward a uniform sample, or with probability goal_bias toward a uniformly chosen node of the
// other tree; after each added node, if the other tree's nearest node is within `range` and the
// connecting edge is valid, the trees are joined and the path returned.
RrtResult PlanBiRrt(const RrtProblem& problem, const RrtOptions& options, const ValidityFn& valid,
                    std::mt19937* rng);

// Checks every edge of `path` at `resolution` (the RRT edge rule; waypoint 0 included). Returns
// true if all checked states are valid; adds the number of validity calls to *checks if given.
bool PathIsValid(const Trajectory& path, double resolution, const ValidityFn& valid,
                 std::int64_t* checks = nullptr);

}  // namespace planning
