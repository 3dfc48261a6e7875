// Trajectories and the status vocabulary shared by every planner (AICO, RRT, BiRRT).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "base/enum_names.h"

namespace planning {

// Outcome of a solver or planner run. "No path" and "did not converge" are statuses, never
// exceptions; exceptions are reserved for invalid input at a public boundary.
enum class SolveStatus {
  kConverged,        // AICO: belief step below tolerance; RRT: a path to the goal was found.
  kMaxIterations,    // AICO: iteration limit reached before convergence (the result is usable).
  kBudgetExhausted,  // RRT: the validity-check budget ran out without a path (counts as failure).
  kDiverged,         // AICO: no accepted sweep within the backtracking limit / non-finite cost.
  kInvalidInput,     // invalid start or goal (e.g. in collision) detected by the planner.
  kSolved,  // AICO run by a scenario with aico.stop_when_solved: stopped at the first accepted
            // sweep whose trajectory meets the scenario's success criteria, before the solve
            // ended (planner.h RunAicoAttempts).
};

inline constexpr base::EnumName<SolveStatus> kSolveStatusNames[] = {
    {SolveStatus::kConverged, "converged"},
    {SolveStatus::kMaxIterations, "max_iterations"},
    {SolveStatus::kBudgetExhausted, "budget_exhausted"},
    {SolveStatus::kDiverged, "diverged"},
    {SolveStatus::kInvalidInput, "invalid_input"},
    {SolveStatus::kSolved, "solved"},
};
constexpr std::span<const base::EnumName<SolveStatus>> EnumNames(SolveStatus) {
  return kSolveStatusNames;
}

// Human-readable name ("converged", "max_iterations", "budget_exhausted", ...).
inline const char* StatusName(SolveStatus status) { return base::ToName(status); }

// A joint-space trajectory: column t of `q` is the configuration q_t (num_dofs × num_points),
// sampled every `dt` seconds (dt = 0 for geometric paths without timing, e.g. RRT output).
struct Trajectory {
  Eigen::MatrixXd q;
  double dt = 0.0;

  int num_points() const { return static_cast<int>(q.cols()); }
  int num_dofs() const { return static_cast<int>(q.rows()); }
};

// Euclidean joint-space length Σ_t |q_{t+1} − q_t|.
double PathLength(const Trajectory& trajectory);

// Limit on the number of interpolated states of one edge or one densified/checked path. A finer
// resolution would need more validity checks than any run can make (and, for Densify, more
// memory); it is refused instead of silently overflowing an integer step count.
inline constexpr std::int64_t kMaxEdgeSteps = 10'000'000;

// Steps of an edge of joint-space length `distance` checked at `resolution`:
// max(1, ⌈distance / resolution⌉) (interior states at i/steps, i = 1 .. steps − 1). Throws
// std::invalid_argument when resolution is not > 0, distance is not finite or the count exceeds
// kMaxEdgeSteps.
std::int64_t EdgeSteps(double distance, double resolution);

// Linear interpolation of a path to equally spaced waypoints at most `resolution` apart
// (Euclidean joint-space distance). Every original waypoint is kept. Throws
// std::invalid_argument for resolution <= 0 or more than kMaxEdgeSteps output waypoints.
Trajectory Densify(const Trajectory& trajectory, double resolution);

}  // namespace planning
