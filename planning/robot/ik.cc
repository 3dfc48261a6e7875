// Inverse kinematics by projected Levenberg–Marquardt with multistart (see ik.h).
#include "planning/robot/ik.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/random.h"

namespace planning {
namespace {

constexpr double kMaxDamping = 1e10;  // λ beyond this: no step lowers the cost (a minimum)
constexpr double kMinDamping = 1e-12;
constexpr int kMaxStalls = 8;  // accepted steps in a row that lower the cost by almost nothing

[[noreturn]] void Bad(const std::string& what) { throw std::invalid_argument("SolveIk: " + what); }

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// The targets with unit axes, after checking them.
std::vector<IkTarget> CheckedTargets(const Robot& robot, const std::vector<IkTarget>& targets) {
  if (targets.empty()) Bad("no targets");
  std::vector<IkTarget> out = targets;
  for (size_t i = 0; i < out.size(); ++i) {
    IkTarget& t = out[i];
    std::string where = "target ";
    where.append(std::to_string(i)).append(": ");
    if (t.link < 0 || t.link >= static_cast<int>(robot.links.size())) {
      Bad(where + "link index " + std::to_string(t.link) + " out of range [0, " +
          std::to_string(robot.links.size()) + ")");
    }
    if (!Finite(t.position)) Bad(where + "position is not finite");
    if (!Finite(t.offset)) Bad(where + "offset is not finite");
    if (!(t.position_weight > 0.0) || !std::isfinite(t.position_weight))
      Bad(where + "position_weight must be finite and > 0");
    if (t.axis) {
      if (!(t.axis_weight > 0.0) || !std::isfinite(t.axis_weight))
        Bad(where + "axis_weight must be finite and > 0");
      for (Eigen::Vector3d* v : {&t.axis->local, &t.axis->world}) {
        const double norm = v->norm();
        if (!std::isfinite(norm) || norm < 1e-12)
          Bad(where + "axis directions must be finite, non-zero");
        *v /= norm;
      }
    }
  }
  return out;
}

void CheckIkOptions(const IkOptions& o) {
  if (o.starts < 1) Bad("starts must be >= 1");
  if (o.max_iterations < 1) Bad("max_iterations must be >= 1");
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(o.position_tolerance)) Bad("position_tolerance must be finite and > 0");
  if (!positive(o.axis_tolerance)) Bad("axis_tolerance must be finite and > 0");
  if (!positive(o.initial_damping)) Bad("initial_damping must be finite and > 0");
  if (!positive(o.max_step)) Bad("max_step must be finite and > 0");
}

int NumResiduals(const std::vector<IkTarget>& targets) {
  int m = 0;
  for (const IkTarget& t : targets) m += t.axis ? 6 : 3;
  return m;
}

// Residual e(q) into *e (FK at q into data->kin); J(q) into data->J too when `jacobian`.
void Evaluate(const Robot& robot, const std::vector<IkTarget>& targets, const Eigen::VectorXd& q,
              bool jacobian, IkData* d, Eigen::VectorXd* e) {
  ForwardKinematics(robot, q, &d->kin);
  int row = 0;
  for (const IkTarget& t : targets) {
    const Eigen::Isometry3d& T = d->kin.world_from_link[t.link];
    e->segment<3>(row) = t.position_weight * (t.position - T * t.offset);
    if (jacobian) {
      PointJacobian(robot, d->kin, t.link, t.offset, d->J.middleRows(row, 3));
      d->J.middleRows(row, 3) *= t.position_weight;
    }
    row += 3;
    if (!t.axis) continue;
    const Eigen::Vector3d a = T.linear() * t.axis->local;
    e->segment<3>(row) = t.axis_weight * (t.axis->world - a);
    if (jacobian) {
      FrameJacobian(robot, d->kin, t.link, d->frame_J);
      for (int k = 0; k < d->J.cols(); ++k) {
        const Eigen::Vector3d w = d->frame_J.block<3, 1>(3, k);
        d->J.block<3, 1>(row, k) = t.axis_weight * w.cross(a);
      }
    }
    row += 3;
  }
}

// Errors from a residual: max position distance [m], max axis angle [rad].
void ErrorsOf(const std::vector<IkTarget>& targets, const Eigen::VectorXd& e, double* pos,
              double* axis) {
  *pos = 0.0;
  *axis = 0.0;
  int row = 0;
  for (const IkTarget& t : targets) {
    *pos = std::max(*pos, e.segment<3>(row).norm() / t.position_weight);
    row += 3;
    if (!t.axis) continue;
    const double chord = std::min(2.0, e.segment<3>(row).norm() / t.axis_weight);
    *axis = std::max(*axis, 2.0 * std::asin(chord / 2.0));
    row += 3;
  }
}

// One projected damped least-squares step: solves (JᵀJ + λI) Δq = Jᵀe with the held dofs' steps
// fixed (frozen: 0; at a bound: up to the bound), holding every dof the step would push out of
// its limits and solving again. Leaves Δq in d->dq and q + Δq (inside the box) in d->q_try.
void ProjectedStep(double lambda, double max_step, IkData* d) {
  const int n = static_cast<int>(d->q.size());
  for (int k = 0; k < n; ++k) d->held[k] = d->frozen[k];
  d->dq.setZero();  // the fixed steps of the held dofs
  for (int pass = 0; pass <= n; ++pass) {
    d->A.noalias() = d->J.transpose() * d->J;
    d->A.diagonal().array() += lambda;
    d->g.noalias() = d->J.transpose() * d->e;
    for (int k = 0; k < n; ++k) {
      if (!d->held[k]) continue;
      const double c = d->dq[k];
      d->g -= d->A.col(k) * c;
      d->A.row(k).setZero();
      d->A.col(k).setZero();
      d->A(k, k) = 1.0;
      d->g[k] = c;
    }
    d->llt.compute(d->A);
    d->dq = d->llt.solve(d->g);
    bool clipped = false;
    for (int k = 0; k < n; ++k) {
      if (d->held[k]) continue;
      const double v = d->q[k] + d->dq[k];
      if (v < d->lower[k] || v > d->upper[k]) {
        d->held[k] = 1;
        d->dq[k] = std::clamp(v, d->lower[k], d->upper[k]) - d->q[k];
        clipped = true;
      }
    }
    if (!clipped) break;
    for (int k = 0; k < n; ++k) {
      if (!d->held[k]) d->dq[k] = 0.0;  // the next pass solves them again
    }
  }
  const double largest = d->dq.lpNorm<Eigen::Infinity>();
  if (largest > max_step) d->dq *= max_step / largest;  // stays in the box (the box is convex)
  d->q_try = (d->q + d->dq).cwiseMax(d->lower).cwiseMin(d->upper);
}

// The start configuration `s`: the seed, or uniform in the limits (±π / ±1 m around the seed for
// unbounded revolute / prismatic joints); frozen dofs keep the seed value.
void StartConfiguration(const Robot& robot, const Eigen::VectorXd& seed, int s, std::mt19937* rng,
                        IkData* d) {
  d->q = seed;
  if (s == 0) return;
  for (int k = 0; k < d->q.size(); ++k) {
    if (d->frozen[k]) continue;
    const double half =
        robot.joints[robot.dof_joints[k]].type == JointType::kPrismatic ? 1.0 : std::numbers::pi;
    const double lo = std::isfinite(d->lower[k]) ? d->lower[k] : seed[k] - half;
    const double hi = std::isfinite(d->upper[k]) ? d->upper[k] : seed[k] + half;
    d->q[k] = lo + base::UniformUnit(rng) * (hi - lo);
  }
}

}  // namespace

IkData::IkData(const Robot& robot)
    : kin(robot),
      lower(LowerLimits(robot)),
      upper(UpperLimits(robot)),
      q(Eigen::VectorXd::Zero(num_dofs(robot))),
      q_try(q),
      dq(q),
      g(q),
      frame_J(6, num_dofs(robot)),
      A(num_dofs(robot), num_dofs(robot)),
      llt(num_dofs(robot)),
      held(num_dofs(robot), 0),
      frozen(num_dofs(robot), 0) {
  // A mimic joint's limits bound its master too: value = m·q + offset must stay in [lo, hi].
  for (const Joint& j : robot.joints) {
    if (!j.is_mimic || j.dof < 0 || j.mimic_multiplier == 0.0) continue;
    double lo = (j.limits.lower - j.mimic_offset) / j.mimic_multiplier;
    double hi = (j.limits.upper - j.mimic_offset) / j.mimic_multiplier;
    if (lo > hi) std::swap(lo, hi);
    const double new_lo = std::max(lower[j.dof], lo), new_hi = std::min(upper[j.dof], hi);
    if (new_lo <= new_hi) {  // contradictory limits (a broken file): the master's own are kept
      lower[j.dof] = new_lo;
      upper[j.dof] = new_hi;
    }
  }
}

void IkData::Resize(int num_residuals) {
  if (e.size() == num_residuals) return;
  e.setZero(num_residuals);
  e_try.setZero(num_residuals);
  J.setZero(num_residuals, q.size());
}

IkResult SolveIk(const Robot& robot, const IkProblem& problem, const IkOptions& options,
                 IkData* data) {
  const int n = num_dofs(robot);
  if (!data) Bad("no IkData");
  if (data->q.size() != n || data->kin.world_from_link.size() != robot.links.size())
    Bad("IkData was sized for another robot");
  if (n == 0) Bad("robot '" + robot.name + "' has no movable joints");
  const std::vector<IkTarget> targets = CheckedTargets(robot, problem.targets);
  CheckIkOptions(options);
  IkData& d = *data;

  // The seed: given (moved into the limits) or the middle of the limits.
  Eigen::VectorXd seed(n);
  if (problem.seed.size() != 0 && problem.seed.size() != n) {
    Bad("seed has " + std::to_string(problem.seed.size()) + " entries, robot '" + robot.name +
        "' has " + std::to_string(n) + " degrees of freedom");
  }
  for (int k = 0; k < n; ++k) {
    const double lo = d.lower[k], hi = d.upper[k];
    if (problem.seed.size() == n) {
      if (!std::isfinite(problem.seed[k])) Bad("seed[" + std::to_string(k) + "] is not finite");
      seed[k] = std::clamp(problem.seed[k], lo, hi);
    } else {
      seed[k] = std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : std::clamp(0.0, lo, hi);
    }
  }
  std::fill(d.frozen.begin(), d.frozen.end(), 0);
  for (int k : problem.frozen_dofs) {
    if (k < 0 || k >= n) {
      Bad("frozen dof " + std::to_string(k) + " out of range [0, " + std::to_string(n) + ")");
    }
    const std::string& name = robot.joints[robot.dof_joints[k]].name;
    if (problem.seed.size() == n && seed[k] != problem.seed[k]) {
      Bad("frozen joint '" + name + "' has a seed value outside its limits");
    }
    d.frozen[k] = 1;
  }

  d.Resize(NumResiduals(targets));
  std::mt19937 rng(options.random_seed);
  IkResult result;
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_q = seed, rejected_q;
  int rejected_start = -1;
  for (int s = 0; s < options.starts; ++s) {
    StartConfiguration(robot, seed, s, &rng, &d);
    ++result.starts;
    Evaluate(robot, targets, d.q, true, &d, &d.e);
    double cost = 0.5 * d.e.squaredNorm();
    double lambda = options.initial_damping;
    double pos = 0.0, axis = 0.0;
    ErrorsOf(targets, d.e, &pos, &axis);
    int stalls = 0;
    for (int it = 0; it < options.max_iterations; ++it) {
      if (pos <= options.position_tolerance && axis <= options.axis_tolerance) break;
      ++result.iterations;
      ProjectedStep(lambda, options.max_step, &d);
      if (d.dq.lpNorm<Eigen::Infinity>() < 1e-14) break;  // every free dof is held
      Evaluate(robot, targets, d.q_try, false, &d, &d.e_try);
      const double cost_try = 0.5 * d.e_try.squaredNorm();
      if (cost_try < cost) {
        stalls = cost - cost_try < 1e-12 * cost ? stalls + 1 : 0;
        d.q.swap(d.q_try);
        d.e.swap(d.e_try);
        cost = cost_try;
        Evaluate(robot, targets, d.q, true, &d, &d.e);
        ErrorsOf(targets, d.e, &pos, &axis);
        lambda = std::max(lambda / 3.0, kMinDamping);
        if (stalls >= kMaxStalls) break;
      } else {
        lambda *= 4.0;
        if (lambda > kMaxDamping) break;
      }
    }
    const bool reached = pos <= options.position_tolerance && axis <= options.axis_tolerance;
    if (reached) {
      if (!options.is_valid || options.is_valid(d.q)) {
        result.status = IkStatus::kSolved;
        result.start = s;
        best_q = d.q;
        break;
      }
      if (result.rejected++ == 0) {
        rejected_q = d.q;
        rejected_start = s;
      }
    } else if (cost < best_cost) {
      best_cost = cost;
      best_q = d.q;
      result.start = s;
    }
  }
  if (result.status != IkStatus::kSolved && result.rejected > 0) {
    result.status = IkStatus::kInvalid;
    best_q = rejected_q;
    result.start = rejected_start;
  }
  // Continuous joints: the same pose within π of the seed value.
  for (int k = 0; k < n; ++k) {
    if (std::isfinite(d.lower[k]) || std::isfinite(d.upper[k])) continue;
    if (robot.joints[robot.dof_joints[k]].type == JointType::kPrismatic) continue;
    best_q[k] = seed[k] + std::remainder(best_q[k] - seed[k], 2.0 * std::numbers::pi);
  }
  result.q = best_q;
  IkErrors(robot, IkProblem{targets, {}, {}}, result.q, &d.kin, &result.position_error,
           &result.axis_error);
  return result;
}

void IkErrors(const Robot& robot, const IkProblem& problem, const Eigen::VectorXd& q,
              KinematicsData* kin, double* position_error, double* axis_error) {
  ForwardKinematics(robot, q, kin);
  *position_error = 0.0;
  *axis_error = 0.0;
  for (const IkTarget& t : problem.targets) {
    if (t.link < 0 || t.link >= static_cast<int>(robot.links.size())) Bad("link out of range");
    const Eigen::Isometry3d& T = kin->world_from_link[t.link];
    *position_error = std::max(*position_error, (t.position - T * t.offset).norm());
    if (!t.axis) continue;
    const Eigen::Vector3d a = T.linear() * t.axis->local.normalized();
    const Eigen::Vector3d w = t.axis->world.normalized();
    *axis_error = std::max(*axis_error, std::atan2(a.cross(w).norm(), a.dot(w)));
  }
}

std::vector<int> DofIndices(const Robot& robot, const std::vector<std::string>& joint_names) {
  std::vector<int> out;
  for (const std::string& name : joint_names) {
    const int j = FindJoint(robot, name);
    const Joint& joint = robot.joints[j];
    if (joint.dof < 0 || joint.is_mimic) {
      std::string known;
      for (const std::string& d : DofNames(robot))
        known.append(known.empty() ? "" : ", ").append(d);
      throw std::invalid_argument("joint '" + name + "' is not an independent movable joint (" +
                                  known + ")");
    }
    out.push_back(joint.dof);
  }
  return out;
}

}  // namespace planning
