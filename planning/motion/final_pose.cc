#include "planning/motion/final_pose.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "base/random.h"

namespace planning {
namespace {

// R, r at state x for the tasks active at T; returns c_T(x).
double TaskMessageAtEnd(const MotionProblem& p, const Eigen::VectorXd& x, TaskWorkspace* ws,
                        Eigen::MatrixXd* R, Eigen::VectorXd* r) {
  const int n = static_cast<int>(p.q0.size());
  const int T = p.num_steps;
  const Eigen::VectorXd q = x.head(n);
  EvaluateTasks(p, T, q, true, ws);
  R->setZero();
  r->setZero();
  double cost = 0.0;
  for (size_t i = 0; i < p.tasks.size(); ++i) {
    const Task& task = p.tasks[i];
    const double rho = task.precision[T];
    if (rho <= 0.0) continue;
    const Eigen::MatrixXd& J = ws->J[i];
    if (task.order == 0) {
      const Eigen::VectorXd e = task.target.col(T) - ws->y[i];
      cost += rho * e.squaredNorm();
      R->topLeftCorner(n, n).noalias() += rho * J.transpose() * J;
      r->head(n).noalias() += rho * J.transpose() * (e + J * q);
    } else if (p.dynamic) {
      const Eigen::VectorXd qdot = x.tail(n);
      cost += rho * (task.target.col(T) - J * qdot).squaredNorm();
      R->bottomRightCorner(n, n).noalias() += rho * J.transpose() * J;
      r->tail(n).noalias() += rho * J.transpose() * task.target.col(T);
    }
  }
  return cost;
}

}  // namespace

FinalPoseResult EstimateFinalPose(const MotionProblem& p, const FinalPoseOptions& options,
                                  TaskWorkspace* ws, const Eigen::VectorXd* init_q) {
  ValidateProblem(p);
  const int n = static_cast<int>(p.q0.size());
  const int d = state_dim(p);
  const int T = p.num_steps;
  const double dt = tau(p);
  if (init_q != nullptr && (init_q->size() != n || !init_q->allFinite())) {
    throw std::invalid_argument("EstimateFinalPose: init has size " +
                                std::to_string(init_q->size()) + ", expected " + std::to_string(n));
  }
  const Eigen::VectorXd metric = p.metric.size() > 0 ? p.metric : Eigen::VectorXd::Ones(n);

  // Prior N(μ_T, Σ_T).
  Eigen::VectorXd x0(d);
  x0.head(n) = p.q0;
  if (p.dynamic) x0.tail(n) = p.qdot0.size() > 0 ? p.qdot0 : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd mu = x0;
  Eigen::MatrixXd sigma = Eigen::MatrixXd::Zero(d, d);
  if (p.dynamic) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Identity(d, d);
    A.topRightCorner(n, n).diagonal().setConstant(dt);
    const Eigen::VectorXd hinv = (p.h_rate * dt * metric).cwiseInverse();
    const double b1 = 0.5 * dt * dt, b2 = dt;
    Eigen::MatrixXd qbar = Eigen::MatrixXd::Zero(d, d);
    qbar.topLeftCorner(n, n).diagonal() = b1 * b1 * hinv;
    qbar.topRightCorner(n, n).diagonal() = b1 * b2 * hinv;
    qbar.bottomLeftCorner(n, n).diagonal() = b1 * b2 * hinv;
    qbar.bottomRightCorner(n, n).diagonal() = b2 * b2 * hinv;
    qbar.diagonal().array() += p.q_rate * dt;
    for (int k = 0; k < T; ++k) {
      sigma = A * sigma * A.transpose() + qbar;
      mu = A * mu;
    }
  } else {
    sigma.diagonal() = T * (p.w_rate * metric).cwiseInverse();
  }
  sigma *= options.prior_scale;
  const Eigen::MatrixXd sigma_inv = sigma.llt().solve(Eigen::MatrixXd::Identity(d, d));
  const Eigen::VectorXd sigma_inv_mu = sigma_inv * mu;

  auto total_cost = [&](const Eigen::VectorXd& x, double task) {
    const Eigen::VectorXd e = x - mu;
    return task + e.dot(sigma_inv * e);
  };

  FinalPoseResult result;
  const long evals0 = ws->evaluations;
  Eigen::VectorXd x = x0;
  if (init_q != nullptr) x.head(n) = *init_q;
  Eigen::MatrixXd R(d, d), Binv(d, d);
  Eigen::VectorXd r(d);
  double task = TaskMessageAtEnd(p, x, ws, &R, &r);
  double best_cost = total_cost(x, task);
  Eigen::VectorXd best_x = x;
  Eigen::MatrixXd best_R = R;
  Eigen::VectorXd best_r = r;
  double best_task = task;
  double alpha = options.alpha;
  for (int it = 0; it < options.max_iterations && alpha >= options.min_alpha; ++it) {
    ++result.iterations;
    Binv = sigma_inv + best_R;
    Binv.diagonal().array() += 1e-10;
    const Eigen::VectorXd b = Binv.llt().solve(sigma_inv_mu + best_r);
    x = best_x + alpha * (b - best_x);
    task = TaskMessageAtEnd(p, x, ws, &R, &r);
    const double cost = total_cost(x, task);
    if (!std::isfinite(cost) || cost > best_cost) {
      alpha *= 0.5;
      continue;
    }
    const double decrease = best_cost - cost;
    best_cost = cost;
    best_x = x;
    best_R = R;
    best_r = r;
    best_task = task;
    alpha = std::sqrt(alpha);
    if (decrease < options.tolerance) break;
  }
  result.x = best_x;
  result.q = best_x.head(n);
  result.precision = sigma_inv + best_R;
  result.cost = best_cost;
  result.task_cost = best_task;
  result.evaluations = ws->evaluations - evals0;
  return result;
}

}  // namespace planning

namespace planning {

FinalPoseSearchResult SearchFinalPose(const MotionProblem& p, const FinalPoseOptions& options,
                                      const FinalPoseSearch& search, TaskWorkspace* ws,
                                      const std::vector<Eigen::VectorXd>& inits,
                                      const EndViolationFn& violation) {
  if (inits.empty()) throw std::invalid_argument("SearchFinalPose: no initial configuration");
  FinalPoseOptions refine = options;
  refine.prior_scale *= search.refine_scale;
  FinalPoseSearchResult out;
  bool have = false;
  auto consider = [&](const FinalPoseResult& r) {
    ++out.candidates;
    const double v = violation(r.q);
    const bool better =
        !have || v < out.violation || (v == out.violation && v == 0.0 && r.cost < out.best.cost);
    if (better) {
      out.best = r;
      out.violation = v;
      have = true;
    }
    return v;
  };
  auto run = [&](const Eigen::VectorXd& init) {
    const FinalPoseResult first = EstimateFinalPose(p, options, ws, &init);
    if (consider(first) > 0.0 && search.refine_scale > 1.0) {
      consider(EstimateFinalPose(p, refine, ws, &first.q));
    }
  };
  run(inits[0]);
  if (out.violation == 0.0) return out;
  for (size_t k = 1; k < inits.size(); ++k) run(inits[k]);
  std::mt19937 rng(search.seed);
  for (int k = 0; k < search.random_starts; ++k) {
    Eigen::VectorXd init = inits[0];
    for (Eigen::Index j = 0; j < init.size(); ++j)
      init[j] += search.spread * (2.0 * base::UniformUnit(&rng) - 1.0);
    run(init);
  }
  return out;
}

}  // namespace planning
