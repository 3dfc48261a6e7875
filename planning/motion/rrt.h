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
#include <memory>
#include <random>
#include <vector>

#include "planning/motion/trajectory.h"

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

// The goal sampler's share of a goal-region run (goal_region.h); all zero for a goal state.
struct GoalSamplerStats {
  std::int64_t draws = 0;         // sampler calls (a candidate drawn and tested against G)
  std::int64_t in_region = 0;     // candidates in the region G (then checked for validity)
  std::int64_t samples = 0;       // of those, valid: goal states the planner used
  std::int64_t checks = 0;        // validity calls on candidates (included in RrtResult::checks)
  std::int64_t region_tests = 0;  // G(q) calls on tree nodes (the uni-directional goal test)
};

struct RrtResult {
  SolveStatus status = SolveStatus::kBudgetExhausted;
  Trajectory path;              // start .. goal waypoints (tree nodes), empty on failure
  std::int64_t checks = 0;      // validity-function calls made by this run
  std::int64_t iterations = 0;  // sampling iterations
  int tree_size = 0;            // total number of nodes in all trees
  GoalSamplerStats goal;        // goal-region runs only
};

// One tree node: configuration and the index of its parent (−1 for the root).
struct RrtNode {
  Eigen::VectorXd q;
  int parent = -1;
};

// Resumable RRT / BiRRT (the algorithms of PlanRrt / PlanBiRrt below): the constructor checks the
// arguments (throws as PlanRrt), copies the problem, options and checker, and checks the start and
// goal states (invalid → done() with kInvalidInput); Step(k) grows up to k iterations. The trees
// are readable between steps. Running Step to the end gives bit-identical paths, checks,
// iterations and trees to PlanRrt / PlanBiRrt with the same generator state; Step(1) repeated
// equals one Step(max). Not thread-safe except RequestStop.
class RrtSolver {
 public:
  // `rng`: the generator state to start from (PlanRrt's *rng); `seed`: std::mt19937(seed).
  RrtSolver(const RrtProblem& problem, const RrtOptions& options, ValidityFn valid,
            std::mt19937 rng, bool bidirectional);
  RrtSolver(const RrtProblem& problem, const RrtOptions& options, ValidityFn valid,
            std::uint64_t seed, bool bidirectional);
  ~RrtSolver();
  RrtSolver(const RrtSolver&) = delete;
  RrtSolver& operator=(const RrtSolver&) = delete;

  // Runs up to k >= 0 sampling iterations; stops early when a path is found, the check budget or
  // max_iterations is reached (done() afterwards) or a stop was requested. Returns the number of
  // iterations run by this call.
  std::int64_t Step(std::int64_t k);
  // Asks a running or future Step to return at the next iteration boundary and ends the run
  // (done(), status kBudgetExhausted unless already finished). Safe to call from another thread.
  void RequestStop();
  bool stop_requested() const;

  bool done() const;
  // kConverged (path found), kInvalidInput, or kBudgetExhausted (also while running: no path yet).
  SolveStatus status() const;
  std::int64_t checks() const;      // validity calls so far (start and goal included)
  std::int64_t iterations() const;  // sampling iterations so far
  int num_trees() const;            // 1 (RRT: rooted at start) or 2 (BiRRT: start, goal)
  // Nodes of tree i in insertion order; node 0 is the root, parents index into the same tree.
  const std::vector<RrtNode>& tree(int i) const;
  // The result so far (path empty until found).
  RrtResult result() const;
  // The generator state after the iterations run so far.
  const std::mt19937& rng() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Uni-directional RRT (LaValle 1998) from start toward goal with goal bias: each iteration draws
// q_rand uniformly in the box (or q_rand = goal with probability goal_bias), extends the nearest
// node by at most `range`, and adds the new node if the edge is valid. Succeeds when an added node
// is the goal itself. Checks the start state first (invalid start or goal → kInvalidInput).
// Throws std::invalid_argument on inconsistent sizes, non-finite values or lower > upper.
// Deterministic for a given *rng state (advanced as the run consumed it). A loop over RrtSolver.
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
