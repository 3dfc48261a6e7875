// Private: the AICO solver's state machine behind AicoSolver and SolveAico
// (planning/motion/aico.h). The messages (task, forward, backward, belief, relocation) are computed
// in aico_messages.cc, the initialisation, sweeps and accept/reject logic in aico.cc.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "planning/features/task.h"
#include "planning/motion/aico.h"
#include "planning/motion/trajectory.h"

namespace planning::internal {

// The solver's view of one run: problem, options, workspace and derived constants.
class Aico {
 public:
  Aico(const MotionProblem& p, const AicoOptions& o, AicoWorkspace* ws)
      : p_(p),
        o_(o),
        ws_(ws),
        n_(static_cast<int>(p.q0.size())),
        d_(state_dim(p)),
        T_(p.num_steps),
        tau_(tau(p)),
        lambda_(o.damping) {
    SetUpProcess();
  }

  // Initialises the beliefs (rollout or `init`) and their cost; done() if max_iterations <= 0.
  void Start(const Trajectory* init);
  // One sweep with its accept/reject decision and convergence test; a no-op once done().
  AicoStep Step();
  bool done() const { return last_.done; }
  const AicoStep& last() const { return last_; }
  const AicoResult& result() const { return result_; }
  double lambda() const { return lambda_; }
  const AicoState& state() const { return ws_->state; }

 private:
  AicoState& st() { return ws_->state; }

  void SetUpProcess();
  void Initialise(const Trajectory* init);
  Trajectory Rollout();
  void TaskMessage(int t, const Eigen::VectorXd& x);
  double BetweenMessage(int t);
  // CountJumps (task.h) of the q part of the current beliefs.
  int Jumps();
  void InvertSpd(const Eigen::MatrixXd& m, Eigen::MatrixXd* out);
  // The message (mean m, precision Minv) arriving at neighbour slice k combined with k's task
  // message (r, R): w.Sbar = (Minv + R_k)⁻¹, w.vtmp2 = w.Sbar (r_k + Minv m). The shared first step
  // of the forward (k = t − 1) and backward (k = t + 1) updates.
  void AbsorbTaskMessage(int k, const Eigen::MatrixXd& Minv, const Eigen::VectorXd& m);
  void UpdateForward(int t);
  void UpdateBackward(int t);
  void UpdateBelief(int t);
  bool Relocate(int t, bool force, double fraction);
  double ControlCost(const AicoState& s) const;
  double EvaluateAll();
  void Sweep(int sweep);
  void Export(AicoResult* result) const;
  void Finish(SolveStatus status);
  // Sets result_'s counters (task evaluations, collision queries, narrow-phase calls) since the
  // solve began.
  void Count();

  const MotionProblem& p_;
  const AicoOptions o_;
  AicoWorkspace* ws_;
  int n_, d_, T_;
  double tau_, lambda_;
  AicoResult result_;
  AicoStep last_;
  int backtracks_ = 0;
  bool guarded_ = false;  // some task has max_jump > 0
  int jumps_ = 0;         // CountJumps of the accepted beliefs
  int max_between_ = 0;   // largest Task::between
  Eigen::MatrixXd qguard_;
  long evals0_ = 0, coll0_ = 0, narrow0_ = 0;
  QueryCounts counts0_;  // TaskQueryCounts when the solve began
  Eigen::VectorXd metric_;
  std::vector<Eigen::VectorXd> err_;  // per task residual buffer, allocated once per run
  // The non-zero rows of the task Jacobians of one message, each scaled by √(its weight), stacked
  // for one rank-k update per block (order-0 rows: the q block; order-1 rows: the q̇ block) instead
  // of one per task: collision, clearance and limit features are zero on most rows away from
  // contact, and the small updates are dominated by their call overhead. Capacity (set in Start):
  // every row of every task at the slice and at its 2 × `between` between states.
  Eigen::MatrixXd gram_q_, gram_v_;
  Eigen::Index rows_q_ = 0, rows_v_ = 0;
  Eigen::MatrixXd linv_;  // d × d: InvertSpd's L⁻¹
  // Appends √w × the non-zero rows of J to `stack` (w >= 0); FlushGram adds the stacks' Gram
  // matrices GᵀG to R's blocks (lower triangles; TaskMessage mirrors R at its end).
  void StackRows(const Eigen::MatrixXd& J, double w, Eigen::MatrixXd* stack, Eigen::Index* rows);
  void FlushGram(Eigen::MatrixXd* R);
};

}  // namespace planning::internal
