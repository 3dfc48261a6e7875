// AICO: approximate inference control (Toussaint, ICML 2009), kinematic and pseudo-dynamic
// (double-integrator) variants, with Levenberg-style damping (docs/methods.md §5).
//
// Model: x_{t+1} = A x_t + B u_t + ξ, ξ ~ N(0, Q), u ~ N(0, H⁻¹); task factors exp(−c_t(x_t)).
//   kinematic: x = q, A = I, transition covariance W⁻¹.
//   dynamic:   x = (q, q̇), A = [[I, τI], [0, I]], B = [[½τ²I], [τI]], H = h_rate·τ·W,
//              Q = q_rate·τ·I; Q̄ = Q + B H⁻¹ Bᵀ.
// Messages per slice t = 0..T (d = state dimension):
//   forward   S̄ = (S_{t−1}⁻¹ + R_{t−1})⁻¹, s_t = A S̄ (S_{t−1}⁻¹ s_{t−1} + r_{t−1}),
//             S_t = Q̄ + A S̄ Aᵀ (kinematic: s_t = S̄(…), S_t = W⁻¹ + S̄); s_0 = x_0, S_0⁻¹ = 10¹⁰ I.
//   backward  V̄ = (V_{t+1}⁻¹ + R_{t+1})⁻¹, v_t = A⁻¹ V̄ (V_{t+1}⁻¹ v_{t+1} + r_{t+1}),
//             V_t = A⁻¹ (Q̄ + V̄) A⁻ᵀ (kinematic: V_t = W⁻¹ + V̄); v_T = b_T, V_T⁻¹ = 10⁻⁴ I (dynamic)
//             or I (kinematic).
//   task      linearised at x̂_t: R_t = Σ ρ JᵀJ, r_t = Σ ρ Jᵀ (y* − φ(q̂) + J q̂) (position block);
//             velocity block Σ ν JᵀJ and Σ ν Jᵀ v* for order-1 tasks; tasks with `between` > 0
//             add the states between x̂_t and its neighbours x̂_{t±1} (held fixed), Jacobian
//             scaled by the weight of q_t in the interpolation.
//   belief    B_t⁻¹ = S_t⁻¹ + V_t⁻¹ + R_t + λI, b_t = B_t (S_t⁻¹ s_t + V_t⁻¹ v_t + r_t + λ
//   b_ref,t).
// Relocation: when |b_t − x̂_t|∞ > tolerance, x̂_t ← b_t (moved at most max_step), task message and
// belief recomputed (dynamic problems: threshold, move and cap on the q half only; the q̇ half
// enters no task message); repeated relocations of one step move x̂_t by relocation_damping·(b_t −
// x̂_t). After each sweep the true cost (task.h) is evaluated at the beliefs; a sweep
// that raises it is rejected (state restored, λ ← 10λ), otherwise λ ← λ/5; so is a sweep whose
// beliefs have more jumps of the tasks with max_jump > 0 (task.h CountJumps) than before it.
// Converged when a sweep moves the beliefs by less than `tolerance` (max norm); if that sweep is
// rejected, the accepted state before it is the result.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "planning/features/task.h"
#include "planning/motion/trajectory.h"

namespace planning {

enum class SweepMode {
  kForwardly,         // relocate once per step in the forward pass (forced in the first sweep)
  kSymmetric,         // relocate once per step in both passes
  kLocalGaussNewton,  // up to max_relocations per step in both passes after the first sweep,
                      // the 2nd and later damped (relocation_damping)
};

struct AicoOptions {
  int max_iterations = 20;  // accepted + rejected sweeps
  double tolerance = 1e-2;  // belief-step convergence and relocation threshold (max norm)
  double damping = 1.0;     // initial λ
  SweepMode sweep_mode = SweepMode::kForwardly;
  double max_step = 1.0;  // cap on one relocation move |x̂_new − x̂| (2-norm)
  // Local Gauss–Newton sweeps: at most this many relocations per step and pass (>= 1).
  int max_relocations = 5;
  // Fraction of b_t − x̂_t by which the 2nd and later relocations of one step move x̂_t (local
  // Gauss–Newton sweeps; the first moves all the way). In (0, 1]; 1 = undamped, which on the unwrap
  // problem keeps moving 0.03–0.1 rad per relocation instead of settling.
  double relocation_damping = 0.3;
  int max_backtracks = 10;  // consecutive rejected sweeps before giving up (kDiverged)
  // Accept the first sweep whatever its cost (Toussaint's implementation's rule: the initial
  // trajectory is only a linearisation point). If false, the first sweep must beat the cost of
  // the initial trajectory too.
  bool accept_first_sweep = true;
  // Task-space rollout initialisation (the "plan in topology space, then map to joint space"
  // hierarchy): when no init trajectory is given, q_t for t = 1..T is found by damped
  // Gauss–Newton from q_{t−1} on  rollout_prior·||q − q_{t−1}||² + Σ_i ρ_{i,t}||y*_{i,t} −
  // φ_i(q)||² (order-0 tasks), with steps capped at max_step. It tracks interpolated targets (e.g.
  // a writhe target moving from y(q_0) to y_T) in small steps, so the initial trajectory does not
  // jump through obstacles between time slices. false: q_0 repeated (Toussaint's cold start).
  bool rollout_init = false;
  double rollout_prior = 100.0;  // precision of the step to the previous slice
  int rollout_iterations = 10;   // Gauss–Newton iterations per slice
};

// All messages and beliefs of one AICO state (one entry per slice t = 0..T).
struct AicoState {
  std::vector<Eigen::VectorXd> s, v, r, b, xhat, bref;
  std::vector<Eigen::MatrixXd> Sinv, Vinv, R, Binv;
  std::vector<double> rhat, task_cost;
  double cost = 0.0;
};

// Preallocated state (current + backup for rejected sweeps) and scratch. Sized from the problem;
// reuse it for repeated solves of problems with the same sizes.
struct AicoWorkspace {
  explicit AicoWorkspace(const MotionProblem& problem);
  AicoState state, backup;
  TaskWorkspace tasks;
  Eigen::MatrixXd A, Ainv, Qbar, Winv, Sbar, tmp, tmp2, eye;
  Eigen::VectorXd vtmp, vtmp2, q, qdot, qbetween;
  Eigen::LLT<Eigen::MatrixXd> llt;
};

struct AicoResult {
  SolveStatus status = SolveStatus::kMaxIterations;
  Trajectory trajectory;       // q part of the beliefs, T+1 columns, dt = τ
  Eigen::MatrixXd velocities;  // q̇ part (dynamic variant), n × (T+1); empty otherwise
  // Cost of each accepted sweep (preceded by the initial trajectory's cost when
  // accept_first_sweep is false); non-increasing.
  std::vector<double> cost_history;
  double cost = 0.0;            // final total cost
  double task_cost = 0.0;       // its task part
  double control_cost = 0.0;    // its control part
  int iterations = 0;           // sweeps run (accepted + rejected)
  int rejected = 0;             // rejected sweeps
  long task_evaluations = 0;    // EvaluateTasks calls (one kinematics + features pass each)
  long collision_queries = 0;   // narrow-phase queries made by collision features
  long narrow_phase_calls = 0;  // FCL narrow-phase calls inside those queries
  // The common cost units (collision.h QueryCounts) spent by this solve: state queries (task
  // evaluation passes that queried the world, one per configuration) and pair tests.
  QueryCounts counts;
};

// Called after every sweep: sweep index (0-based), its cost, whether it was accepted, and the
// current trajectory (the restored one after a rejection).
using AicoCallback =
    std::function<void(int sweep, double cost, bool accepted, const Trajectory& trajectory)>;

// One sweep's outcome (AicoSolver::Step). `status` is the solver's status after the sweep:
// kMaxIterations while it is still running (the result so far is usable), the final status once
// `done` (kConverged, kMaxIterations, kDiverged). `cost` is the true cost of the sweep's beliefs
// (the rejected ones' too); `sweep` its 0-based index.
struct AicoStep {
  SolveStatus status = SolveStatus::kMaxIterations;
  int sweep = -1;
  double cost = 0.0;
  bool accepted = false;
  bool done = false;
};

// Resumable AICO (the shape of Crocoddyl's/OMPL's solvers): the constructor validates the input
// (as SolveAico), builds its own AicoWorkspace, initialises the beliefs (rollout or `init`, T+1
// configurations; copied) and evaluates their cost; Step() runs exactly one sweep. Keeps a
// reference to `problem` (it must outlive the solver and stay unchanged); copies `options`.
// Stepping to the end gives bit-identical results to Solve() and to SolveAico.
class AicoSolver {
 public:
  AicoSolver(const MotionProblem& problem, const AicoOptions& options,
             const Trajectory* init = nullptr);
  ~AicoSolver();
  AicoSolver(const AicoSolver&) = delete;
  AicoSolver& operator=(const AicoSolver&) = delete;

  // One sweep (forward and backward pass, cost at the beliefs, accept or reject with the damping
  // update, convergence test). After done() a no-op returning the last step again.
  AicoStep Step();
  // Steps until done; `callback` after each sweep (sweep, cost, accepted, trajectory()).
  AicoResult Solve(const AicoCallback& callback = {});

  bool done() const;
  int sweeps() const;      // sweeps run so far (accepted + rejected)
  double cost() const;     // true cost of the current (last accepted) beliefs
  double damping() const;  // current λ
  // q part of the current beliefs, n × (T+1), dt = τ (the restored beliefs after a rejection).
  const Trajectory& trajectory() const;
  // All messages and beliefs, per slice (d = state dimension).
  const AicoState& state() const;
  // The result so far (status kMaxIterations while running); the final one once done().
  AicoResult result() const;
  // result().counts without copying the result: the state queries and pair tests so far.
  const QueryCounts& counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Runs AICO from `init` (T+1 configurations; nullptr = q0 repeated, zero velocity). Throws
// std::invalid_argument for an invalid problem (ValidateProblem) or init size; returns a status
// for non-convergence. No allocation inside sweeps once `ws` exists.
AicoResult SolveAico(const MotionProblem& problem, const AicoOptions& options, AicoWorkspace* ws,
                     const AicoCallback& callback = {}, const Trajectory* init = nullptr);

// Total cost (task.h) of a trajectory q (n × (T+1)) with velocities (dynamic; empty = finite
// differences q̇_t = (q_{t+1} − q_t)/τ, last = 0). Evaluates tasks through `ws`.
double TrajectoryCost(const MotionProblem& problem, const Eigen::MatrixXd& q,
                      const Eigen::MatrixXd& qdot, TaskWorkspace* ws, double* task_cost = nullptr,
                      double* control_cost = nullptr);

}  // namespace planning
