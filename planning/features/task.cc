#include "planning/features/task.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace planning {

void SetConstantTarget(Task* task, const Eigen::VectorXd& y, double precision, int num_steps) {
  task->target = y.replicate(1, num_steps + 1);
  task->precision = Eigen::VectorXd::Constant(num_steps + 1, precision);
}

void SetInterpolatedTarget(Task* task, const Eigen::VectorXd& y0, const Eigen::VectorXd& yT,
                           double mid, double final, int num_steps) {
  if (y0.size() != yT.size()) {
    throw std::invalid_argument("SetInterpolatedTarget(" + task->name + "): y0 has size " +
                                std::to_string(y0.size()) + ", yT " + std::to_string(yT.size()));
  }
  task->target.resize(y0.size(), num_steps + 1);
  for (int t = 0; t <= num_steps; ++t) {
    const double s = static_cast<double>(t) / num_steps;
    task->target.col(t) = (1.0 - s) * y0 + s * yT;
  }
  task->precision = Eigen::VectorXd::Constant(num_steps + 1, mid);
  task->precision[num_steps] = final;
}

void ValidateProblem(const MotionProblem& p) {
  if (p.robot == nullptr) throw std::invalid_argument("motion problem: no robot");
  const int n = num_dofs(*p.robot);
  if (p.q0.size() != n || !p.q0.allFinite()) {
    throw std::invalid_argument("motion problem: q0 has size " + std::to_string(p.q0.size()) +
                                ", the robot has " + std::to_string(n) + " dofs (or non-finite)");
  }
  if (p.qdot0.size() != 0 && (p.qdot0.size() != n || !p.qdot0.allFinite())) {
    throw std::invalid_argument("motion problem: qdot0 must be empty or of size " +
                                std::to_string(n));
  }
  if (p.num_steps < 1 || !(p.duration > 0.0) || !(p.h_rate > 0.0) || !(p.w_rate > 0.0) ||
      !(p.q_rate >= 0.0)) {
    throw std::invalid_argument(
        "motion problem: need num_steps >= 1, duration > 0, h_rate > 0, w_rate > 0, q_rate >= 0");
  }
  if (p.metric.size() != 0 && (p.metric.size() != n || !(p.metric.minCoeff() > 0.0))) {
    throw std::invalid_argument("motion problem: metric must be empty or " + std::to_string(n) +
                                " positive values");
  }
  for (const Task& task : p.tasks) {
    const std::string who = "task '" + task.name + "'";
    if (!task.feature) throw std::invalid_argument(who + ": no feature");
    if (task.target.rows() != task.feature->dim() || task.target.cols() != p.num_steps + 1) {
      throw std::invalid_argument(who + ": target is " + std::to_string(task.target.rows()) + "x" +
                                  std::to_string(task.target.cols()) + ", expected " +
                                  std::to_string(task.feature->dim()) + "x" +
                                  std::to_string(p.num_steps + 1));
    }
    if (task.precision.size() != p.num_steps + 1 || !task.precision.allFinite() ||
        task.precision.minCoeff() < 0.0 || !task.target.allFinite()) {
      throw std::invalid_argument(who +
                                  ": precision must have T+1 = " + std::to_string(p.num_steps + 1) +
                                  " finite non-negative values and the target must be finite");
    }
    if (task.order != 0 && task.order != 1)
      throw std::invalid_argument(who + ": order must be 0|1");
    if (task.between < 0 || (task.between > 0 && task.order != 0))
      throw std::invalid_argument(who + ": between must be >= 0 (and 0 for order-1 tasks)");
    if (!(task.max_jump >= 0.0) ||
        (task.max_jump > 0.0 && (task.order != 0 || task.feature->dim() != 1)))
      throw std::invalid_argument(who + ": max_jump must be >= 0 (and 0 unless order 0, dim 1)");
  }
}

TaskWorkspace::TaskWorkspace(const MotionProblem& problem) : kin(*problem.robot) {
  const int n = num_dofs(*problem.robot);
  for (const Task& task : problem.tasks) {
    data.push_back(task.feature->CreateData(*problem.robot));
    y.emplace_back(Eigen::VectorXd::Zero(task.feature->dim()));
    J.emplace_back(Eigen::MatrixXd::Zero(task.feature->dim(), n));
  }
}

void EvaluateTasks(const MotionProblem& problem, int t, const Eigen::VectorXd& q, bool jacobians,
                   TaskWorkspace* ws) {
  ForwardKinematics(*problem.robot, q, &ws->kin);
  ++ws->evaluations;
  bool world = false;
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    const Task& task = problem.tasks[i];
    if (t >= 0 && task.precision[t] <= 0.0) continue;
    task.feature->Eval(*problem.robot, ws->kin, ws->data[i].get(), ws->y[i],
                       jacobians ? &ws->J[i] : nullptr);
    world |= task.feature->queries_world();
  }
  if (world) ++ws->state_queries;
}

void EvaluateTask(const MotionProblem& problem, int i, const Eigen::VectorXd& q, bool jacobians,
                  TaskWorkspace* ws) {
  ForwardKinematics(*problem.robot, q, &ws->kin);
  ++ws->evaluations;
  const Task& task = problem.tasks[static_cast<size_t>(i)];
  task.feature->Eval(*problem.robot, ws->kin, ws->data[i].get(), ws->y[i],
                     jacobians ? &ws->J[i] : nullptr);
  if (task.feature->queries_world()) ++ws->state_queries;
}

bool EvaluateBetweenTasks(const MotionProblem& problem, int t, int between,
                          const Eigen::VectorXd& q, bool jacobians, TaskWorkspace* ws) {
  auto active = [&](const Task& task) {
    return task.between == between && task.precision[t] > 0.0;
  };
  if (std::none_of(problem.tasks.begin(), problem.tasks.end(), active)) return false;
  ForwardKinematics(*problem.robot, q, &ws->kin);
  ++ws->evaluations;
  bool world = false;
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    const Task& task = problem.tasks[i];
    if (!active(task)) continue;
    task.feature->Eval(*problem.robot, ws->kin, ws->data[i].get(), ws->y[i],
                       jacobians ? &ws->J[i] : nullptr);
    world |= task.feature->queries_world();
  }
  if (world) ++ws->state_queries;
  return true;
}

int MaxBetween(const MotionProblem& problem) {
  int max_between = 0;
  for (const Task& task : problem.tasks) max_between = std::max(max_between, task.between);
  return max_between;
}

double BetweenCost(const MotionProblem& problem, int t, const Eigen::VectorXd& q_prev,
                   const Eigen::VectorXd& q, TaskWorkspace* ws) {
  double cost = 0.0;
  const int max_between = MaxBetween(problem);
  for (int count = 1; count <= max_between; ++count) {
    for (int k = 1; k <= count; ++k) {
      const double alpha = static_cast<double>(k) / (count + 1);
      if (!EvaluateBetweenTasks(problem, t, count, (1.0 - alpha) * q_prev + alpha * q, false, ws)) {
        break;
      }
      for (size_t i = 0; i < problem.tasks.size(); ++i) {
        const Task& task = problem.tasks[i];
        if (task.between != count || task.precision[t] <= 0.0) continue;
        cost += task.precision[t] * (task.target.col(t) - ws->y[i]).squaredNorm();
      }
    }
  }
  return cost;
}

int CountJumps(const MotionProblem& problem, const Eigen::MatrixXd& q, TaskWorkspace* ws) {
  int jumps = 0;
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    const Task& task = problem.tasks[i];
    if (task.max_jump <= 0.0) continue;
    const int task_index = static_cast<int>(i);
    EvaluateTask(problem, task_index, q.col(0), false, ws);
    double prev = ws->y[i][0];
    for (Eigen::Index t = 1; t < q.cols(); ++t) {
      for (int k = 1; k <= task.between + 1; ++k) {
        const double alpha = static_cast<double>(k) / (task.between + 1);
        EvaluateTask(problem, task_index, (1.0 - alpha) * q.col(t - 1) + alpha * q.col(t), false,
                     ws);
        const double y = ws->y[i][0];
        if (std::abs(y - prev) >= task.max_jump) ++jumps;
        prev = y;
      }
    }
  }
  return jumps;
}

double TaskCost(const MotionProblem& problem, int t, const Eigen::VectorXd& qdot,
                const TaskWorkspace& ws) {
  double cost = 0.0;
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    const Task& task = problem.tasks[i];
    const double rho = task.precision[t];
    if (rho <= 0.0) continue;
    if (task.order == 0) {
      cost += rho * (task.target.col(t) - ws.y[i]).squaredNorm();
    } else if (qdot.size() > 0) {
      for (Eigen::Index r = 0; r < ws.J[i].rows(); ++r) {
        const double e = task.target(r, t) - ws.J[i].row(r).dot(qdot);
        cost += rho * e * e;
      }
    } else {
      cost += rho * task.target.col(t).squaredNorm();
    }
  }
  return cost;
}

QueryCounts TaskQueryCounts(const MotionProblem& problem, const TaskWorkspace& ws) {
  QueryCounts total;
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    total += problem.tasks[i].feature->query_counts(ws.data[i].get());
  }
  total.state_queries = ws.state_queries;
  return total;
}

long CollisionQueries(const MotionProblem& problem, const TaskWorkspace& ws) {
  long total = 0;
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    total += problem.tasks[i].feature->collision_queries(ws.data[i].get());
  }
  return total;
}

long NarrowPhaseCalls(const MotionProblem& problem, const TaskWorkspace& ws) {
  long total = 0;
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    total += problem.tasks[i].feature->narrow_phase_calls(ws.data[i].get());
  }
  return total;
}

}  // namespace planning
