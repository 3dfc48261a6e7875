// AICO (planning/motion/aico.h): the solver loop — initialisation (rollout or given trajectory),
// sweeps, cost, accept/reject with the damping update, convergence — and the public entry points
// AicoSolver, SolveAico, TrajectoryCost. The messages of one sweep are in aico_messages.cc.
#include "planning/motion/aico.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/numbers.h"
#include "planning/motion/internal/aico_solver.h"

namespace planning {
namespace {

constexpr double kStartPrecision = 1e10;  // S_0⁻¹: the start state is fixed

void ResizeState(int slices, int d, AicoState* st) {
  for (auto* vecs : {&st->s, &st->v, &st->r, &st->b, &st->xhat, &st->bref}) {
    vecs->assign(slices, Eigen::VectorXd::Zero(d));
  }
  for (auto* mats : {&st->Sinv, &st->Vinv, &st->R, &st->Binv}) {
    mats->assign(slices, Eigen::MatrixXd::Zero(d, d));
  }
  st->rhat.assign(slices, 0.0);
  st->task_cost.assign(slices, 0.0);
}

// Control cost of the step from slice t to t + 1: h_rate/τ · Σ_i metric_i (to_i − from_i)² for
// dynamic problems (from, to: the two slices' velocities), w_rate · Σ_i metric_i (to_i − from_i)²
// for kinematic ones (from, to: the two slices' positions). All vectors have size n.
double StepControlCost(const MotionProblem& p, const Eigen::VectorXd& metric, double tau,
                       const Eigen::Ref<const Eigen::VectorXd>& from,
                       const Eigen::Ref<const Eigen::VectorXd>& to) {
  const double sum = ((to - from).array().square() * metric.array()).sum();
  return p.dynamic ? p.h_rate / tau * sum : p.w_rate * sum;
}

}  // namespace

// ---- The solver loop (internal::Aico, planning/motion/internal/aico_solver.h) ----------------

namespace internal {

int Aico::Jumps() {
  qguard_.resize(n_, T_ + 1);
  for (int t = 0; t <= T_; ++t) qguard_.col(t) = st().b[t].head(n_);
  return CountJumps(p_, qguard_, &ws_->tasks);
}

double Aico::ControlCost(const AicoState& s) const {
  double cost = 0.0;
  for (int t = 0; t < T_; ++t) {
    // The velocity half of the state for dynamic problems, the whole (position) state otherwise.
    cost += StepControlCost(p_, metric_, tau_, s.b[t].tail(n_), s.b[t + 1].tail(n_));
  }
  return cost;
}

// Task messages at x̂ = b for every slice; returns the total cost.
double Aico::EvaluateAll() {
  AicoState& s = st();
  double task = 0.0;
  for (int t = 0; t <= T_; ++t) s.xhat[t] = s.b[t];  // (the between terms read the neighbours)
  for (int t = 0; t <= T_; ++t) {
    TaskMessage(t, s.xhat[t]);
    task += s.task_cost[t];
  }
  s.cost = task + ControlCost(s);
  return s.cost;
}

// Per slice t: damped Gauss–Newton from q_{t−1} on the prior step cost plus the order-0 tasks.
Trajectory Aico::Rollout() {
  Trajectory out;
  out.dt = tau_;
  out.q.resize(n_, T_ + 1);
  out.q.col(0) = p_.q0;
  TaskWorkspace& tw = ws_->tasks;
  Eigen::MatrixXd H(n_, n_);
  Eigen::VectorXd g(n_), q(n_), step(n_), prev(n_), trial(n_);
  Eigen::LLT<Eigen::MatrixXd> llt(n_);
  const double rho_p = o_.rollout_prior;
  // Cost at x; evaluates the tasks with Jacobians into tw and their residuals into err_, which
  // system() then turns into the GN system at the same x without evaluating again.
  auto cost_at = [&](int t, const Eigen::VectorXd& x) {
    EvaluateTasks(p_, t, x, true, &tw);
    double c = rho_p * (x - prev).squaredNorm();
    for (size_t i = 0; i < p_.tasks.size(); ++i) {
      const Task& task = p_.tasks[i];
      const double rho = task.precision[t];
      if (rho <= 0.0 || task.order != 0) continue;
      err_[i] = task.target.col(t) - tw.y[i];
      c += rho * err_[i].squaredNorm();
    }
    return c;
  };
  auto system = [&](int t, const Eigen::VectorXd& x) {
    H.setZero();
    H.diagonal().setConstant(rho_p);
    g = rho_p * (x - prev);
    for (size_t i = 0; i < p_.tasks.size(); ++i) {
      const Task& task = p_.tasks[i];
      const double rho = task.precision[t];
      if (rho <= 0.0 || task.order != 0) continue;
      H.noalias() += rho * tw.J[i].transpose() * tw.J[i];
      g.noalias() -= rho * tw.J[i].transpose() * err_[i];
    }
  };
  for (int t = 1; t <= T_; ++t) {
    prev = out.q.col(t - 1);
    q = prev;
    double mu = 1e-3;
    double cost = cost_at(t, q);
    system(t, q);
    for (int it = 0; it < o_.rollout_iterations; ++it) {
      H.diagonal().array() += mu;
      llt.compute(H);
      step = -g;
      llt.solveInPlace(step);
      const double norm = step.norm();
      if (norm > o_.max_step) step *= o_.max_step / norm;
      trial = q + step;
      const double c = cost_at(t, trial);
      if (std::isfinite(c) && c < cost) {
        q = trial;
        mu = std::max(1e-6, mu / 5.0);
        cost = c;
        system(t, q);
        if (step.lpNorm<Eigen::Infinity>() < 1e-4) break;
      } else {
        H.diagonal().array() -= mu;
        mu *= 10.0;
      }
    }
    out.q.col(t) = q;
  }
  return out;
}

void Aico::Initialise(const Trajectory* init) {
  AicoState& s = st();
  for (int t = 0; t <= T_; ++t) {
    Eigen::VectorXd& x = s.b[t];
    if (init != nullptr) {
      x.head(n_) = init->q.col(t);
      if (p_.dynamic) {
        x.tail(n_) = t < T_ ? ((init->q.col(t + 1) - init->q.col(t)) / tau_).eval()
                            : Eigen::VectorXd::Zero(n_);
      }
    } else {
      x.head(n_) = p_.q0;
      if (p_.dynamic) x.tail(n_).setZero();
    }
    s.xhat[t] = x;
    s.bref[t] = x;
    s.s[t] = x;
    s.v[t] = x;
    s.Sinv[t] = lambda_ * ws_->eye;
    s.Vinv[t] = lambda_ * ws_->eye;
    s.Binv[t] = ws_->eye;
  }
  // The start slice is fixed.
  s.b[0].head(n_) = p_.q0;
  if (p_.dynamic) {
    if (p_.qdot0.size() > 0) {
      s.b[0].tail(n_) = p_.qdot0;
    } else {
      s.b[0].tail(n_).setZero();
    }
  }
  s.s[0] = s.b[0];
  s.Sinv[0] = kStartPrecision * ws_->eye;
  EvaluateAll();
}

void Aico::Sweep(int sweep) {
  int fwd_reloc = 1, bwd_reloc = 0;
  if (o_.sweep_mode == SweepMode::kSymmetric && sweep > 0) bwd_reloc = 1;
  if (o_.sweep_mode == SweepMode::kLocalGaussNewton && sweep > 0) {
    fwd_reloc = bwd_reloc = o_.max_relocations;
  }
  for (int t = 1; t <= T_; ++t) {
    UpdateForward(t);
    UpdateBelief(t);
    for (int k = 0; k < fwd_reloc; ++k) {
      if (!Relocate(t, sweep == 0 && k == 0, k == 0 ? 1.0 : o_.relocation_damping)) break;
    }
  }
  for (int t = T_; t >= 1; --t) {
    UpdateBackward(t);
    UpdateBelief(t);
    for (int k = 0; k < bwd_reloc; ++k) {
      if (!Relocate(t, false, k == 0 ? 1.0 : o_.relocation_damping)) break;
    }
  }
}

void Aico::Export(AicoResult* result) const {
  const AicoState& s = ws_->state;
  result->trajectory.dt = tau_;
  result->trajectory.q.resize(n_, T_ + 1);
  if (p_.dynamic) result->velocities.resize(n_, T_ + 1);
  double task = 0.0;
  for (int t = 0; t <= T_; ++t) {
    result->trajectory.q.col(t) = s.b[t].head(n_);
    if (p_.dynamic) result->velocities.col(t) = s.b[t].tail(n_);
    task += s.task_cost[t];
  }
  result->cost = s.cost;
  result->task_cost = task;
  result->control_cost = s.cost - task;
}

void Aico::Start(const Trajectory* init) {
  evals0_ = ws_->tasks.evaluations;
  coll0_ = CollisionQueries(p_, ws_->tasks);
  narrow0_ = NarrowPhaseCalls(p_, ws_->tasks);
  counts0_ = TaskQueryCounts(p_, ws_->tasks);
  err_.clear();
  Eigen::Index rows_q = 1, rows_v = 1;
  for (const Task& task : p_.tasks) {
    const Eigen::Index dim = task.feature->dim();
    err_.emplace_back(Eigen::VectorXd::Zero(dim));
    if (task.order == 0) {
      rows_q += dim * (1 + 2 * std::max(task.between, 0));  // the slice and its between states
    } else {
      rows_v += dim;
    }
  }
  max_between_ = MaxBetween(p_);
  gram_q_.resize(rows_q, n_);
  gram_v_.resize(rows_v, n_);
  linv_.resize(d_, d_);
  Trajectory rollout;
  if (init == nullptr && o_.rollout_init) {
    rollout = Rollout();
    init = &rollout;
  }
  Initialise(init);
  guarded_ = false;
  for (const Task& task : p_.tasks) guarded_ = guarded_ || task.max_jump > 0.0;
  jumps_ = guarded_ ? Jumps() : 0;
  if (!o_.accept_first_sweep) result_.cost_history.push_back(st().cost);
  backtracks_ = 0;
  last_ = AicoStep{};
  if (o_.max_iterations <= 0) {
    Finish(SolveStatus::kMaxIterations);
  } else {
    Export(&result_);
    Count();
  }
}

void Aico::Finish(SolveStatus status) {
  result_.status = status;
  last_.status = status;
  last_.done = true;
  Export(&result_);
  Count();
}

void Aico::Count() {
  result_.task_evaluations = ws_->tasks.evaluations - evals0_;
  result_.collision_queries = CollisionQueries(p_, ws_->tasks) - coll0_;
  result_.narrow_phase_calls = NarrowPhaseCalls(p_, ws_->tasks) - narrow0_;
  result_.counts = TaskQueryCounts(p_, ws_->tasks) - counts0_;
}

AicoStep Aico::Step() {
  if (last_.done) return last_;
  const int sweep = result_.iterations;
  ws_->backup = ws_->state;  // same sizes: no allocation
  Sweep(sweep);
  // Belief step against the previous sweep's belief, then the true cost at the beliefs.
  double b_step = 0.0;
  for (int t = 0; t <= T_; ++t) {
    b_step = std::max(b_step, (st().b[t] - st().bref[t]).lpNorm<Eigen::Infinity>());
    st().bref[t] = st().b[t];
  }
  const double cost = EvaluateAll();
  ++result_.iterations;
  const bool cost_ok =
      std::isfinite(cost) && (cost <= ws_->backup.cost || (sweep == 0 && o_.accept_first_sweep));
  // The jumps decide only between sweeps the cost accepts (a rejected sweep's count is not kept).
  const int jumps = guarded_ && cost_ok ? Jumps() : 0;
  const bool accepted = cost_ok && jumps <= jumps_;
  if (!accepted) {
    std::swap(ws_->state, ws_->backup);
    lambda_ *= 10.0;
    ++result_.rejected;
    ++backtracks_;
  } else {
    lambda_ /= 5.0;
    backtracks_ = 0;
    jumps_ = jumps;
    result_.cost_history.push_back(cost);
  }
  last_ = AicoStep{SolveStatus::kMaxIterations, sweep, cost, accepted, false};
  // A rejected sweep that moved the beliefs by less than the tolerance leaves the accepted state
  // converged: at a stationary point the cost of such sweeps differs only by rounding, and
  // rejecting them until max_backtracks would report a solved problem as diverged.
  if (b_step < o_.tolerance) {
    Finish(SolveStatus::kConverged);
  } else if (backtracks_ > o_.max_backtracks) {
    Finish(SolveStatus::kDiverged);
  } else if (result_.iterations >= o_.max_iterations) {
    Finish(SolveStatus::kMaxIterations);
  } else {
    Export(&result_);
    Count();
  }
  return last_;
}

}  // namespace internal

namespace {

void CheckInput(const MotionProblem& problem, const AicoOptions& options, const Trajectory* init) {
  ValidateProblem(problem);
  if (init != nullptr && (init->num_dofs() != problem.q0.size() ||
                          init->num_points() != problem.num_steps + 1 || !init->q.allFinite())) {
    throw std::invalid_argument(
        "SolveAico: init trajectory is " + std::to_string(init->num_dofs()) + "x" +
        std::to_string(init->num_points()) + ", expected " + std::to_string(problem.q0.size()) +
        "x" + std::to_string(problem.num_steps + 1));
  }
  if (options.max_relocations < 1) {
    throw std::invalid_argument("SolveAico: need max_relocations >= 1, got " +
                                std::to_string(options.max_relocations));
  }
  if (!(options.relocation_damping > 0.0 && options.relocation_damping <= 1.0)) {
    throw std::invalid_argument("SolveAico: need relocation_damping in (0, 1], got " +
                                base::FormatShortest(options.relocation_damping));
  }
  if (!(options.tolerance > 0.0) || !(options.damping >= 0.0) || !(options.max_step > 0.0) ||
      options.max_iterations < 0) {
    throw std::invalid_argument("SolveAico: need tolerance > 0, damping >= 0, max_step > 0");
  }
}

// Steps `aico` until done, calling `callback` after each sweep.
AicoResult RunAicoToEnd(internal::Aico* aico, const AicoCallback& callback) {
  while (!aico->done()) {
    const AicoStep step = aico->Step();
    if (callback) callback(step.sweep, step.cost, step.accepted, aico->result().trajectory);
  }
  return aico->result();
}

}  // namespace

AicoWorkspace::AicoWorkspace(const MotionProblem& problem) : tasks(problem) {
  const int d = state_dim(problem), n = static_cast<int>(problem.q0.size());
  ResizeState(problem.num_steps + 1, d, &state);
  ResizeState(problem.num_steps + 1, d, &backup);
  for (auto* m : {&A, &Ainv, &Qbar, &Winv, &Sbar, &tmp, &tmp2, &eye}) m->setZero(d, d);
  vtmp.setZero(d);
  vtmp2.setZero(d);
  q.setZero(n);
  qdot.setZero(n);
  qbetween.setZero(n);
  // Preallocates by factorising I_d (assigning a fresh LLT(d) would copy its uninitialised info).
  llt.compute(Eigen::MatrixXd::Identity(d, d));
}

struct AicoSolver::Impl {
  Impl(const MotionProblem& p, const AicoOptions& o) : ws(p), aico(p, o, &ws) {}
  AicoWorkspace ws;
  internal::Aico aico;
};

AicoSolver::AicoSolver(const MotionProblem& problem, const AicoOptions& options,
                       const Trajectory* init) {
  CheckInput(problem, options, init);
  impl_ = std::make_unique<Impl>(problem, options);
  impl_->aico.Start(init);
}

AicoSolver::~AicoSolver() = default;

AicoStep AicoSolver::Step() { return impl_->aico.Step(); }

AicoResult AicoSolver::Solve(const AicoCallback& callback) {
  return RunAicoToEnd(&impl_->aico, callback);
}

bool AicoSolver::done() const { return impl_->aico.done(); }
int AicoSolver::sweeps() const { return impl_->aico.result().iterations; }
double AicoSolver::cost() const { return impl_->aico.state().cost; }
double AicoSolver::damping() const { return impl_->aico.lambda(); }
const Trajectory& AicoSolver::trajectory() const { return impl_->aico.result().trajectory; }
const AicoState& AicoSolver::state() const { return impl_->aico.state(); }
AicoResult AicoSolver::result() const { return impl_->aico.result(); }
const QueryCounts& AicoSolver::counts() const { return impl_->aico.result().counts; }

AicoResult SolveAico(const MotionProblem& problem, const AicoOptions& options, AicoWorkspace* ws,
                     const AicoCallback& callback, const Trajectory* init) {
  const int d = state_dim(problem);
  ValidateProblem(problem);
  if (ws == nullptr || static_cast<int>(ws->state.b.size()) != problem.num_steps + 1 ||
      ws->state.b[0].size() != d) {
    throw std::invalid_argument("SolveAico: workspace was built for another problem size");
  }
  CheckInput(problem, options, init);
  internal::Aico aico(problem, options, ws);
  aico.Start(init);
  return RunAicoToEnd(&aico, callback);
}

double TrajectoryCost(const MotionProblem& problem, const Eigen::MatrixXd& q,
                      const Eigen::MatrixXd& qdot, TaskWorkspace* ws, double* task_cost,
                      double* control_cost) {
  const int T = problem.num_steps;
  const int n = static_cast<int>(problem.q0.size());
  if (q.rows() != n || q.cols() != T + 1) {
    throw std::invalid_argument("TrajectoryCost: q must be " + std::to_string(n) + "x" +
                                std::to_string(T + 1));
  }
  const double dt = tau(problem);
  Eigen::MatrixXd v = qdot;
  if (problem.dynamic && v.size() == 0) {
    v.setZero(n, T + 1);
    for (int t = 0; t < T; ++t) v.col(t) = (q.col(t + 1) - q.col(t)) / dt;
  }
  const Eigen::VectorXd metric =
      problem.metric.size() > 0 ? problem.metric : Eigen::VectorXd::Ones(n);
  double task = 0.0, control = 0.0;
  for (int t = 0; t <= T; ++t) {
    EvaluateTasks(problem, t, q.col(t), true, ws);
    task +=
        TaskCost(problem, t, problem.dynamic ? Eigen::VectorXd(v.col(t)) : Eigen::VectorXd(), *ws);
    if (t > 0) task += BetweenCost(problem, t, q.col(t - 1), q.col(t), ws);
    if (t < T) {
      const Eigen::MatrixXd& x = problem.dynamic ? v : q;
      control += StepControlCost(problem, metric, dt, x.col(t), x.col(t + 1));
    }
  }
  if (task_cost != nullptr) *task_cost = task;
  if (control_cost != nullptr) *control_cost = control;
  return task + control;
}

}  // namespace planning
