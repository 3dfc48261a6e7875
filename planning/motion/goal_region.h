// RRT and BiRRT toward a goal region instead of one goal state (issue 35, item 3: the baselines
// get the same goal information as AICO). Shape after OMPL's GoalSampleableRegion (isSatisfied,
// sampleGoal) and GoalLazySamples (goal states produced on demand, here synchronously and seeded):
//
//   G ⊂ box  the goal region, given by a membership test G(q) (the end conditions; validity is the
//            planner's) and a sampler that draws a candidate q̃ and reports whether q̃ ∈ G;
//   goal state  a candidate with q̃ ∈ G that passed the validity check (counted, same budget).
//
// Everything else is rrt.h's: the box, the validity checker (one counted call per state), the edge
// rule at `resolution`, `range`, the check budget, the iteration cap.
//
// Uni-directional (rrt-region): each iteration extends the tree (nearest node, at most `range`)
// toward a uniform sample, or with probability goal_bias toward a goal state of the pool chosen
// uniformly (a uniform sample while the pool is empty); the run succeeds when an added node q_new
// has G(q_new) (tested on every added node).
// Bi-directional (birrt-region, RRTConnect with several goal states): the start tree and a goal
// forest (one root per goal state) grow alternately as in PlanBiRrt (target: a uniform sample, or
// with probability goal_bias a uniformly chosen node of the other tree); the trees are joined
// through the other tree's nearest node within `range`. Until the first goal state is found only
// the start tree grows.
// Lazy goal states (both): at most one candidate is drawn per iteration (uni: on goal-biased
// iterations only), and only while the goal states m < max_goal_states and (m = 0 or m < N/2),
// N = nodes of the tree the goal states feed (uni: the start tree; bi: the goal forest) — OMPL
// RRTConnect's rule for adding goal roots. A run whose sampler never yields a goal state keeps
// growing toward uniform samples until the budget ends it (kBudgetExhausted).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "planning/motion/rrt.h"

namespace planning {

struct GoalRegion {
  // G(q): q meets the goal conditions (not its validity). Must be set.
  std::function<bool(const Eigen::VectorXd& q)> contains;
  // One draw: writes a candidate q̃ (size n) to *q from *rng (the planner's generator) and returns
  // G(q̃). Must be set; deterministic given the generator state.
  std::function<bool(std::mt19937* rng, Eigen::VectorXd* q)> sample;
  // Validity of candidates in G (empty: the planner's checker). Counted in the planner's checks and
  // budget, and in GoalSamplerStats::checks.
  ValidityFn valid;
};

struct GoalRegionProblem {
  Eigen::VectorXd lower, upper;  // joint box
  Eigen::VectorXd start;         // q_0
  GoalRegion goal;
};

inline constexpr int kDefaultMaxGoalStates = 32;  // the scenario key rrt.goal_states' default

// A scenario's goal-region settings (its "rrt" object): max_goal_states (rrt.goal_states, the
// GoalRegionOptions field), and the sampler of scenario_goal_region.h: IK iterations per start
// (rrt.goal_ik_iterations) and uniform starts per draw (rrt.goal_ik_starts).
struct ScenarioGoalSettings {
  int max_goal_states = kDefaultMaxGoalStates;
  int ik_iterations = 200;
  int ik_starts = 1;
};

struct GoalRegionOptions {
  RrtOptions rrt;  // range, resolution, goal_bias, max_checks, max_iterations (rrt.h)
  // >= 1: the pool (uni) / goal roots (bi) grow to at most this many
  int max_goal_states = kDefaultMaxGoalStates;
};

// Resumable goal-region RRT / BiRRT (the interface of RrtSolver). The constructor checks the
// arguments (std::invalid_argument: sizes, non-finite values, lower > upper, contains or sample
// unset, max_goal_states < 1, range/resolution as PlanRrt), copies them, checks the start state
// (invalid → done(), kInvalidInput) and tests G(start) (→ done(), kConverged, path = start).
// Step(k) runs up to k iterations; running to the end gives the same result whatever the chunks.
class GoalRegionSolver {
 public:
  GoalRegionSolver(const GoalRegionProblem& problem, const GoalRegionOptions& options,
                   ValidityFn valid, std::uint64_t seed, bool bidirectional);
  ~GoalRegionSolver();
  GoalRegionSolver(const GoalRegionSolver&) = delete;
  GoalRegionSolver& operator=(const GoalRegionSolver&) = delete;

  // Runs up to k >= 0 iterations; stops early on a path, the budget, max_iterations or a stop
  // request. Returns the iterations run by this call.
  std::int64_t Step(std::int64_t k);
  // Ends the run at the next iteration boundary (kBudgetExhausted unless finished); thread-safe.
  void RequestStop();
  bool done() const;
  SolveStatus status() const;  // kConverged, kInvalidInput or kBudgetExhausted
  int num_trees() const;       // 1 (start tree) or 2 (start tree, goal forest)
  // Nodes of tree i (insertion order; parents index into the same tree, −1 for a root).
  const std::vector<RrtNode>& tree(int i) const;
  // Goal states found so far (the pool; bi: the goal roots), in the order found.
  const std::vector<Eigen::VectorXd>& goal_states() const;
  // checks include the sampler's (result().goal.checks); path: start .. a state in G.
  RrtResult result() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Runs a GoalRegionSolver with std::mt19937(seed) to the end.
RrtResult PlanGoalRegion(const GoalRegionProblem& problem, const GoalRegionOptions& options,
                         const ValidityFn& valid, std::uint64_t seed, bool bidirectional);

}  // namespace planning
