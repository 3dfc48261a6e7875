// Tasks (feature + per-step target + precision) and the motion problem that AICO solves.
//
// Cost of a trajectory x_{0:T} (x = q, or x = (q, q̇) in the dynamic variant):
//   C = Σ_t Σ_i ρ_{i,t} ||y*_{i,t} − φ_i(q_t)||²          (order-0 tasks)
//     + Σ_t Σ_i ν_{i,t} ||y*_{i,t} − J_i(q_t) q̇_t||²      (order-1 tasks, dynamic variant only)
//     + Σ_t Σ_k ρ_{i,t} ||y*_{i,t} − φ_i(q_t(α_k))||²   (tasks with `between` > 0: states between
//                                                    slices t − 1 and t, see Task::between)
//     + control cost: kinematic Σ_t ||q_{t+1} − q_t||²_W, dynamic Σ_t (h/τ) ||q̇_{t+1} − q̇_t||²_W
// with τ = duration / T and W = w_rate·diag(metric) (docs/methods.md §4).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "planning/features/feature.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"

namespace planning {

struct Task {
  std::string name;                  // for reports and messages
  std::unique_ptr<Feature> feature;  // φ
  Eigen::MatrixXd target;            // dim × (T+1): column t = y*_t
  Eigen::VectorXd precision;         // size T+1: ρ_t (0 = inactive at t)
  int order = 0;                     // 0: position term; 1: velocity term (dynamic variant)
  // Order-0 tasks only: K >= 0 extra states per step. The task is also evaluated between
  // neighbouring slices, at q_t(α_k) = (1 − α_k) q_{t−1} + α_k q_t with α_k = k/(K+1), k = 1..K
  // (target y*_t, precision ρ_t), adding Σ_k ρ_t ||y*_t − φ(q_t(α_k))||² per step t = 1..T to
  // the cost, so e.g. collision is seen on the straight joint-space motion between slices.
  int between = 0;
  // > 0 (order-0 tasks of dim 1, e.g. the winding about a pole's line): a continuity guard, not a
  // cost. AICO rejects a sweep whose beliefs have more jumps |Δφ| >= max_jump between neighbouring
  // states (slices and the `between` states) than the beliefs before it: a jump is a change of
  // homotopy class (the arm tunnelling through the pole between slices), which no local cost sees.
  double max_jump = 0.0;
};

// target_t = y for all t; precision_t = `precision` for all t.
void SetConstantTarget(Task* task, const Eigen::VectorXd& y, double precision, int num_steps);

// Linearly interpolated target y*_t = (1 − t/T)·y0 + (t/T)·yT; precision `mid` for t < T and
// `final` at t = T (as in Toussaint's AICO code).
void SetInterpolatedTarget(Task* task, const Eigen::VectorXd& y0, const Eigen::VectorXd& yT,
                           double mid, double final, int num_steps);

struct MotionProblem {
  const Robot* robot = nullptr;
  std::vector<Task> tasks;
  Eigen::VectorXd q0;      // start configuration (size n)
  Eigen::VectorXd qdot0;   // start velocity (dynamic variant); empty = 0
  int num_steps = 50;      // T (T+1 time slices 0..T)
  double duration = 2.0;   // seconds; τ = duration / T
  bool dynamic = true;     // pseudo-dynamic double integrator (x = (q, q̇)) or kinematic (x = q)
  double h_rate = 0.1;     // control-cost rate (dynamic): H = h_rate·τ·W
  double w_rate = 1.0;     // transition metric rate (kinematic): W = w_rate·diag(metric)
  double q_rate = 1e-10;   // process-noise rate (dynamic): Q = q_rate·τ·I
  Eigen::VectorXd metric;  // diagonal of W_rate (size n); empty = all ones
};

inline double tau(const MotionProblem& p) { return p.duration / p.num_steps; }
inline int state_dim(const MotionProblem& p) {
  return p.dynamic ? 2 * static_cast<int>(p.q0.size()) : static_cast<int>(p.q0.size());
}

// Throws std::invalid_argument naming the task when sizes disagree (q0 vs robot, target rows vs
// feature dim, columns vs T+1, precision size) or values are non-finite / negative.
void ValidateProblem(const MotionProblem& problem);

// Buffers for evaluating all tasks at one configuration (allocated once).
struct TaskWorkspace {
  explicit TaskWorkspace(const MotionProblem& problem);
  KinematicsData kin;
  std::vector<std::unique_ptr<FeatureData>> data;  // per task
  std::vector<Eigen::VectorXd> y;                  // per task, φ_i(q)
  std::vector<Eigen::MatrixXd> J;                  // per task, dim_i × n
  long evaluations = 0;                            // number of EvaluateTasks calls
  // Evaluation passes (EvaluateTasks, EvaluateTask, EvaluateBetweenTasks calls) that evaluated at
  // least one feature that queries the world (Feature::queries_world): one state query per
  // configuration, however many collision/clearance features it evaluates.
  long state_queries = 0;
};

// ForwardKinematics at q, then every task i that is active at step t (ρ_{i,t} > 0; t < 0: all
// tasks) into ws->y[i] (and ws->J[i] if `jacobians`). No allocation.
void EvaluateTasks(const MotionProblem& problem, int t, const Eigen::VectorXd& q, bool jacobians,
                   TaskWorkspace* ws);

// ForwardKinematics at q, then task i alone into ws->y[i] (and ws->J[i] if `jacobians`).
void EvaluateTask(const MotionProblem& problem, int i, const Eigen::VectorXd& q, bool jacobians,
                  TaskWorkspace* ws);

// Every task i with Task::between == `between` (> 0) that is active at step t (ρ_{i,t} > 0) at q
// into ws->y[i] (and ws->J[i]) after one ForwardKinematics: the tasks that share the states
// between two slices share one kinematics pass. Returns false (and computes nothing) when no
// such task is active. No allocation.
bool EvaluateBetweenTasks(const MotionProblem& problem, int t, int between,
                          const Eigen::VectorXd& q, bool jacobians, TaskWorkspace* ws);

// Largest Task::between of the problem's tasks (0 without between-slice tasks).
int MaxBetween(const MotionProblem& problem);

// The between-slice part of the cost of step t (1 <= t <= T) from slice t − 1 at q_prev to slice
// t at q: Σ_i Σ_k ρ_{i,t} ||y*_{i,t} − φ_i(q_t(α_k))||² over the tasks with between > 0 (see
// Task). Evaluates through `ws` (overwrites its kinematics and those tasks' y and J).
double BetweenCost(const MotionProblem& problem, int t, const Eigen::VectorXd& q_prev,
                   const Eigen::VectorXd& q, TaskWorkspace* ws);

// Number of jumps of the tasks with max_jump > 0 along q (n × (T+1)): per step t and task i,
// the neighbouring pairs among φ_i(q_{t−1}), φ_i(q_t(α_1)), ..., φ_i(q_t(α_K)), φ_i(q_t) (K =
// between_i) whose values differ by max_jump_i or more. Evaluates through `ws`.
int CountJumps(const MotionProblem& problem, const Eigen::MatrixXd& q, TaskWorkspace* ws);

// Task part of the cost at step t from the last EvaluateTasks(t, q, jacobians = true, ws):
// Σ ρ||y* − φ||² over order-0 tasks + Σ ν||y* − J q̇||² over order-1 tasks (q̇ may be empty: 0).
double TaskCost(const MotionProblem& problem, int t, const Eigen::VectorXd& qdot,
                const TaskWorkspace& ws);

// The cost units (collision.h QueryCounts) spent so far through `ws`: state_queries =
// ws.state_queries (per configuration), pair tests summed over the features' query_counts.
QueryCounts TaskQueryCounts(const MotionProblem& problem, const TaskWorkspace& ws);

// Narrow-phase collision queries made so far by all features through `ws`.
long CollisionQueries(const MotionProblem& problem, const TaskWorkspace& ws);
// Shape-pair (narrow-phase) FCL calls made so far by all features through `ws`.
long NarrowPhaseCalls(const MotionProblem& problem, const TaskWorkspace& ws);

}  // namespace planning
