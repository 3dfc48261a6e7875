// AICO messages (planning/motion/aico.h, docs/methods.md §5): the process model (A, A⁻¹, Q̄, W⁻¹),
// the task message R_t, r_t at a linearisation point (with the states between slices), the
// forward and backward messages, the belief and the relocation of x̂_t. Methods of internal::Aico
// (planning/motion/internal/aico_solver.h); the solver loop is in aico.cc.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cassert>
#include <cmath>

#include "planning/motion/internal/aico_solver.h"

namespace planning::internal {
namespace {

// M ← A M Aᵀ for the double integrator's A = [[I, cI], [0, I]] (n × n blocks; c = τ for A,
// −τ for A⁻¹), in O(d²): the rows of the top block gain c × the bottom rows, then the left
// columns gain c × the right columns.
void ApplyTransition(double c, Eigen::MatrixXd* m) {
  const Eigen::Index n = m->rows() / 2;
  m->topRows(n) += c * m->bottomRows(n);
  m->leftCols(n) += c * m->rightCols(n);
}

}  // namespace

void Aico::SetUpProcess() {
  metric_ = p_.metric.size() > 0 ? p_.metric : Eigen::VectorXd::Ones(n_);
  AicoWorkspace& w = *ws_;
  w.eye.setIdentity(d_, d_);
  if (!p_.dynamic) {
    w.A.setIdentity(d_, d_);
    w.Ainv.setIdentity(d_, d_);
    w.Winv.setZero(d_, d_);
    w.Winv.diagonal() = (p_.w_rate * metric_).cwiseInverse();
    w.Qbar = w.Winv;
    return;
  }
  // A = [[I, τI], [0, I]]; A⁻¹ negates the upper-right block.
  w.A.setIdentity(d_, d_);
  w.A.topRightCorner(n_, n_).diagonal().setConstant(tau_);
  w.Ainv.setIdentity(d_, d_);
  w.Ainv.topRightCorner(n_, n_).diagonal().setConstant(-tau_);
  // Q̄ = Q + B H⁻¹ Bᵀ with B = [½τ² I; τ I], H = h_rate·τ·W (diagonal).
  const Eigen::VectorXd hinv = (p_.h_rate * tau_ * metric_).cwiseInverse();
  const double b1 = 0.5 * tau_ * tau_, b2 = tau_;
  w.Qbar.setZero(d_, d_);
  w.Qbar.topLeftCorner(n_, n_).diagonal() = b1 * b1 * hinv;
  w.Qbar.topRightCorner(n_, n_).diagonal() = b1 * b2 * hinv;
  w.Qbar.bottomLeftCorner(n_, n_).diagonal() = b1 * b2 * hinv;
  w.Qbar.bottomRightCorner(n_, n_).diagonal() = b2 * b2 * hinv;
  w.Qbar.diagonal().array() += p_.q_rate * tau_;
  w.Winv = w.Qbar;
}

// M = L Lᵀ, M⁻¹ = L⁻ᵀ L⁻¹: one triangular solve for L⁻¹ and a symmetric product (about 2/3 of the
// flops of solving M X = I with both triangular factors).
void Aico::InvertSpd(const Eigen::MatrixXd& m, Eigen::MatrixXd* out) {
  ws_->llt.compute(m);
  linv_.setIdentity();
  ws_->llt.matrixL().solveInPlace(linv_);
  out->setZero();
  out->selfadjointView<Eigen::Lower>().rankUpdate(linv_.transpose());
  out->triangularView<Eigen::StrictlyUpper>() = out->transpose();
}

void Aico::StackRows(const Eigen::MatrixXd& J, double w, Eigen::MatrixXd* stack,
                     Eigen::Index* rows) {
  const double scale = std::sqrt(w);
  for (Eigen::Index i = 0; i < J.rows(); ++i) {
    if (J.row(i).isZero(0.0)) continue;
    assert(*rows < stack->rows());
    stack->row((*rows)++) = scale * J.row(i);
  }
}

void Aico::FlushGram(Eigen::MatrixXd* R) {
  if (rows_q_ > 0) {
    R->topLeftCorner(n_, n_).selfadjointView<Eigen::Lower>().rankUpdate(
        gram_q_.topRows(rows_q_).transpose());
  }
  if (rows_v_ > 0) {
    R->bottomRightCorner(n_, n_).selfadjointView<Eigen::Lower>().rankUpdate(
        gram_v_.topRows(rows_v_).transpose());
  }
  rows_q_ = rows_v_ = 0;
}

// R_t, r_t, r̂_t and the task cost at x (the linearisation point).
void Aico::TaskMessage(int t, const Eigen::VectorXd& x) {
  AicoWorkspace& w = *ws_;
  w.q = x.head(n_);
  if (p_.dynamic) w.qdot = x.tail(n_);
  EvaluateTasks(p_, t, w.q, true, &w.tasks);
  Eigen::MatrixXd& R = st().R[t];
  Eigen::VectorXd& r = st().r[t];
  R.setZero();
  r.setZero();
  double rhat = 0.0, cost = 0.0;
  for (size_t i = 0; i < p_.tasks.size(); ++i) {
    const Task& task = p_.tasks[i];
    const double rho = task.precision[t];
    if (rho <= 0.0) continue;
    const Eigen::MatrixXd& J = w.tasks.J[i];
    Eigen::VectorXd& e = err_[i];
    if (task.order == 0) {
      e = task.target.col(t) - w.tasks.y[i];
      cost += rho * e.squaredNorm();
      e.noalias() += J * w.q;
      StackRows(J, rho, &gram_q_, &rows_q_);
      r.head(n_).noalias() += rho * J.transpose() * e;
      rhat += rho * e.squaredNorm();
    } else if (p_.dynamic) {
      e = task.target.col(t);
      StackRows(J, rho, &gram_v_, &rows_v_);
      r.tail(n_).noalias() += rho * J.transpose() * e;
      e.noalias() -= J * w.qdot;
      cost += rho * e.squaredNorm();
    }
  }
  st().rhat[t] = rhat;
  st().task_cost[t] = cost + BetweenMessage(t);
  FlushGram(&R);
  R.triangularView<Eigen::StrictlyUpper>() = R.transpose();
}

// Tasks with `between` > 0 (task.h): the states between slice t and each neighbour k = t ± 1,
// held at its linearisation point x̂_k (the Gauss–Newton treatment of the pair factor):
// q(β) = (1 − β) q_t + β q̂_k, so ∂φ(q(β))/∂q_t = (1 − β) J. Adds ρ c² JᵀJ and ρ c Jᵀ(e + c J q̂_t)
// (c = 1 − β, e = y* − φ(q(β)); target and precision of the step's later slice) to R_t, r_t.
// Each such state is seen from both ends of its step: returns half its cost.
double Aico::BetweenMessage(int t) {
  AicoWorkspace& w = *ws_;
  Eigen::VectorXd& r = st().r[t];
  double cost = 0.0;
  for (int k = t - 1; k <= t + 1; k += 2) {
    if (k < 0 || k > T_) continue;
    const int step = std::max(t, k);
    // Tasks with the same `between` count share their states: one kinematics pass per state.
    for (int count = 1; count <= max_between_; ++count) {
      for (int j = 1; j <= count; ++j) {
        const double alpha = static_cast<double>(j) / (count + 1);  // along t−1 → t
        const double c = k < t ? alpha : 1.0 - alpha;               // weight of q_t
        w.qbetween = c * w.q;
        w.qbetween.noalias() += (1.0 - c) * st().xhat[k].head(n_);
        if (!EvaluateBetweenTasks(p_, step, count, w.qbetween, true, &w.tasks)) break;
        for (size_t i = 0; i < p_.tasks.size(); ++i) {
          const Task& task = p_.tasks[i];
          const double rho = task.precision[step];
          if (task.between != count || rho <= 0.0) continue;
          const Eigen::MatrixXd& J = w.tasks.J[i];
          Eigen::VectorXd& e = err_[i];
          e = task.target.col(step) - w.tasks.y[i];
          cost += 0.5 * rho * e.squaredNorm();
          e.noalias() += c * (J * w.q);
          StackRows(J, rho * c * c, &gram_q_, &rows_q_);
          r.head(n_).noalias() += (rho * c) * J.transpose() * e;
        }
      }
    }
  }
  return cost;
}

void Aico::AbsorbTaskMessage(int k, const Eigen::MatrixXd& Minv, const Eigen::VectorXd& m) {
  AicoWorkspace& w = *ws_;
  const AicoState& s = st();
  w.tmp = Minv + s.R[k];
  InvertSpd(w.tmp, &w.Sbar);
  w.vtmp = s.r[k];
  w.vtmp.noalias() += Minv * m;
  w.vtmp2.noalias() = w.Sbar * w.vtmp;
}

void Aico::UpdateForward(int t) {
  AicoWorkspace& w = *ws_;
  AicoState& s = st();
  AbsorbTaskMessage(t - 1, s.Sinv[t - 1], s.s[t - 1]);
  if (p_.dynamic) {
    s.s[t] = w.vtmp2;
    s.s[t].head(n_) += tau_ * w.vtmp2.tail(n_);  // A s̄
    w.tmp = w.Sbar;
    ApplyTransition(tau_, &w.tmp);  // A S̄ Aᵀ
    w.tmp2 = w.Qbar + w.tmp;
  } else {
    s.s[t] = w.vtmp2;
    w.tmp2 = w.Winv + w.Sbar;
  }
  InvertSpd(w.tmp2, &s.Sinv[t]);
}

void Aico::UpdateBackward(int t) {
  AicoWorkspace& w = *ws_;
  AicoState& s = st();
  if (t == T_) {
    s.v[t] = s.b[t];
    s.Vinv[t] = (p_.dynamic ? 1e-4 : 1.0) * w.eye;
    return;
  }
  AbsorbTaskMessage(t + 1, s.Vinv[t + 1], s.v[t + 1]);  // w.Sbar = V̄
  if (p_.dynamic) {
    s.v[t] = w.vtmp2;
    s.v[t].head(n_) -= tau_ * w.vtmp2.tail(n_);  // A⁻¹ v̄
    w.tmp = w.Qbar + w.Sbar;
    ApplyTransition(-tau_, &w.tmp);  // A⁻¹ (Q̄ + V̄) A⁻ᵀ
    InvertSpd(w.tmp, &s.Vinv[t]);
  } else {
    s.v[t] = w.vtmp2;
    w.tmp2 = w.Winv + w.Sbar;
    InvertSpd(w.tmp2, &s.Vinv[t]);
  }
}

void Aico::UpdateBelief(int t) {
  AicoWorkspace& w = *ws_;
  AicoState& s = st();
  s.Binv[t] = s.Sinv[t] + s.Vinv[t] + s.R[t];
  s.Binv[t].diagonal().array() += lambda_;
  w.vtmp = s.r[t] + lambda_ * s.bref[t];
  w.vtmp.noalias() += s.Sinv[t] * s.s[t];
  w.vtmp.noalias() += s.Vinv[t] * s.v[t];
  w.llt.compute(s.Binv[t]);
  s.b[t] = w.vtmp;
  w.llt.solveInPlace(s.b[t]);
}

// The move, its threshold and its cap look at q only: x̂_t's velocity half enters no task message
// (order-1 tasks are linear in q̇ with Jacobians that depend on q), so it simply follows b_t.
bool Aico::Relocate(int t, bool force, double fraction) {
  AicoState& s = st();
  AicoWorkspace& w = *ws_;
  w.vtmp = s.b[t] - s.xhat[t];
  if (p_.dynamic) w.vtmp.tail(n_).setZero();
  if (!force && w.vtmp.lpNorm<Eigen::Infinity>() <= o_.tolerance) return false;
  const double step = w.vtmp.norm();
  const double scale = step > o_.max_step ? o_.max_step / step : 1.0;
  s.xhat[t].noalias() += std::min(scale, fraction) * w.vtmp;
  if (p_.dynamic) s.xhat[t].tail(n_) = s.b[t].tail(n_);
  TaskMessage(t, s.xhat[t]);
  UpdateBelief(t);
  return true;
}

}  // namespace planning::internal
