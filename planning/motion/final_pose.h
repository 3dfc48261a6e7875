// Final-pose estimation (thesis §4.2.2; docs/methods.md §6): the most likely end state x_T under
// the T-step process prior and the task costs active at t = T only.
//
// Prior: x_T ~ N(μ_T, Σ_T) with μ_T = A^T x_0 and Σ_T from Σ ← A Σ Aᵀ + Q̄ (T times, Σ = 0 at
// the start); kinematic: μ_T = q_0, Σ_T = T·W⁻¹. Damped Gauss–Newton, from x = x_0 (or `init`):
//   1. R, r = task message of the t = T tasks at x;
//   2. B⁻¹ = Σ_T⁻¹ + R + 10⁻¹⁰ I, b = B (Σ_T⁻¹ μ_T + r);
//   3. x ← x_old + α (b − x_old);
//   4. cost c_T(x) + ||x − μ_T||²_{Σ_T⁻¹} increased: restore the best x, α ← α/2; else α ← √α;
//   5. stop when α < min_alpha or the decrease is below `tolerance`, or after max_iterations.
// The RRT baselines get q̂_T as their goal; AICO gets task targets evaluated at q̂_T.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "planning/features/task.h"

namespace planning {

struct FinalPoseOptions {
  double alpha = 0.05;      // initial step fraction
  double min_alpha = 1e-3;  // stop below this step fraction
  double tolerance = 1e-5;  // stop when an accepted step lowers the cost by less than this
  int max_iterations = 1000;
  // Scales Σ_T (values > 1 weaken the prior). The thesis calls it with a 4 s horizon.
  double prior_scale = 1.0;
};

struct FinalPoseResult {
  Eigen::VectorXd x;          // state estimate (q, or (q, q̇) in the dynamic variant)
  Eigen::VectorXd q;          // its configuration part
  Eigen::MatrixXd precision;  // posterior precision B⁻¹ at the estimate
  double cost = 0.0;          // c_T(x) + prior term at the estimate
  double task_cost = 0.0;     // c_T(x)
  int iterations = 0;
  long evaluations = 0;  // EvaluateTasks calls
};

// Throws std::invalid_argument for an invalid problem (ValidateProblem) or init of wrong size.
FinalPoseResult EstimateFinalPose(const MotionProblem& problem, const FinalPoseOptions& options,
                                  TaskWorkspace* ws, const Eigen::VectorXd* init_q = nullptr);

// Multi-start search for an end state that meets given end conditions (the goal of a scenario):
// EstimateFinalPose from inits[0], inits[1], ..., then from inits[0] + δ, δ_j uniform in [−spread,
// spread] (random_starts draws, UniformUnit of std::mt19937(seed)), each followed by a second pass
// from its result with the prior weakened by `refine_scale` (prior_scale × refine_scale; <= 1: no
// second pass). `violation(q)` >= 0 scores the end conditions at q (0 = all met). inits[0]'s
// estimate is returned as soon as it meets them; otherwise the met candidate of least cost, or,
// when none meets them, the candidate of least violation. Deterministic.
struct FinalPoseSearch {
  int random_starts = 8;
  double spread = 0.3;  // rad, per joint
  unsigned seed = 1;
  double refine_scale = 10.0;
};
using EndViolationFn = std::function<double(const Eigen::VectorXd& q)>;
struct FinalPoseSearchResult {
  FinalPoseResult best;
  double violation = 0.0;  // violation(best.q)
  int candidates = 0;      // estimates run (first passes and refinements)
};
// Throws std::invalid_argument for an empty `inits`, or as EstimateFinalPose.
FinalPoseSearchResult SearchFinalPose(const MotionProblem& problem, const FinalPoseOptions& options,
                                      const FinalPoseSearch& search, TaskWorkspace* ws,
                                      const std::vector<Eigen::VectorXd>& inits,
                                      const EndViolationFn& violation);

}  // namespace planning
