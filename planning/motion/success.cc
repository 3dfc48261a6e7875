#include "planning/motion/success.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "base/numbers.h"
#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "topology/line_crossing.h"
#include "topology/winding.h"

namespace planning {

inline constexpr base::EnumName<FailureReason> kFailureReasonNames[] = {
    {FailureReason::kNone, "none"},
    {FailureReason::kJointLimits, "joint_limits"},
    {FailureReason::kCollision, "collision"},
    {FailureReason::kTunnelled, "tunnelled"},
    {FailureReason::kWritheNotReached, "writhe_not_reached"},
    {FailureReason::kReachError, "reach_error"},
    {FailureReason::kNotThroughLoop, "not_through_loop"},
    {FailureReason::kBudgetExhausted, "budget_exhausted"},
    {FailureReason::kDiverged, "diverged"},
    {FailureReason::kInvalidInput, "invalid_input"},
};
constexpr std::span<const base::EnumName<FailureReason>> EnumNames(FailureReason) {
  return kFailureReasonNames;
}

const char* FailureReasonName(FailureReason reason) { return base::ToName(reason); }

PlanVerdict JudgePlan(const Scenario& s, const Trajectory& path) {
  return JudgePlan(s, s.initial, path, s.success);
}

PlanVerdict JudgePlan(const Scenario& s, const ScenarioState& w, const Trajectory& path) {
  return JudgePlan(s, w, path, s.success);
}

namespace {

// "joint 'NAME' (q[k]) = v outside [lo, hi] rad|m".
std::string LimitDetail(const Robot& robot, int k, double value) {
  const Joint& joint = robot.joints[robot.dof_joints[k]];
  std::string d = "joint '";
  d.append(joint.name).append("' (q[").append(std::to_string(k)).append("]) = ");
  d.append(base::FormatShortest(value)).append(" outside [");
  d.append(base::FormatShortest(joint.limits.lower)).append(", ");
  d.append(base::FormatShortest(joint.limits.upper)).append("] ");
  d.append(joint.type == JointType::kPrismatic ? "m" : "rad");
  return d;
}

// ReportWinding(q) (turns), minus the winding of the straight segment from the report chain's
// first point to its last when `closed_by_chord` (the chain closed by its chord), from one forward
// kinematics pass.
double EndWinding(const Scenario& s, const ScenarioState& w, const Eigen::VectorXd& q,
                  bool closed_by_chord) {
  if (s.report_chain < 0) return 0.0;
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  Eigen::Matrix3Xd points;
  ChainPoints(s.robot, kin, s.report_chain, &points);
  const topology::Axis axis = ReportAxis(s, w);
  double turns = topology::WindingNumber(points, axis);
  if (closed_by_chord) {
    Eigen::Matrix3Xd chord(3, 2);
    chord << points.col(0), points.col(points.cols() - 1);
    turns -= topology::WindingNumber(chord, axis);
  }
  return turns;
}

// Where the report chain passes the report line while q moves linearly from qa to qb (one
// resampled step with a winding jump): kThrough when a located pass meets the line within the
// report object chain's extent (its first to last point), kBeyondEnds when every located pass
// lies outside it, kUnlocated when none is found (a fast but continuous change, or two passes of
// one segment).
enum class JumpPlace { kThrough, kBeyondEnds, kUnlocated };
JumpPlace LocateJump(const Scenario& s, const ScenarioState& w, const Eigen::VectorXd& qa,
                     const Eigen::VectorXd& qb) {
  KinematicsData kin(s.robot);
  Eigen::VectorXd q(qa.size());
  const topology::ChainMotion motion = [&](double t, topology::Chain* points) {
    q = qa + t * (qb - qa);
    ForwardKinematics(s.robot, q, &kin);
    ChainPoints(s.robot, kin, s.report_chain, points);
  };
  const Eigen::Matrix3Xd& O = w.report_object_chain;
  const auto crossings = topology::LocateLineCrossings(motion, O.col(0), O.col(O.cols() - 1));
  if (crossings.empty()) return JumpPlace::kUnlocated;
  for (const topology::LineCrossing& x : crossings) {
    if (x.line_param >= 0.0 && x.line_param <= 1.0) return JumpPlace::kThrough;
  }
  return JumpPlace::kBeyondEnds;
}

}  // namespace

PlanVerdict JudgePlan(const Scenario& s, const ScenarioState& w, const Trajectory& path,
                      const SuccessCriteria& c) {
  if (path.num_points() == 0) throw std::invalid_argument("JudgePlan: empty path");
  PlanVerdict v;
  CollisionData coll(s.robot, w.env, s.collision);
  KinematicsData kin(s.robot);
  const Eigen::VectorXd lo = LowerLimits(s.robot), hi = UpperLimits(s.robot);
  const bool winding = c.winding_max_jump > 0.0 || c.winding_final_below > 0.0;
  const topology::Axis axis = winding ? ReportAxis(s, w) : topology::Axis{};
  Eigen::Matrix3Xd points;
  std::vector<ProximityPair> pairs;
  const Trajectory dense = Densify(path, s.check_resolution);
  const auto fail = [&v](FailureReason reason, int k) {
    if (v.reason != FailureReason::kNone) return;
    v.reason = reason;
    v.step = k;
  };
  double w_prev = 0.0;
  int tunnel_step = -1;  // first resampled state after a winding jump
  for (int k = 0; k < dense.num_points(); ++k) {
    const auto q = dense.q.col(k);
    if (((q.array() < lo.array()) || (q.array() > hi.array())).any()) {
      if (v.reason == FailureReason::kNone) {
        for (Eigen::Index j = 0; j < q.size(); ++j) {
          if (q[j] >= lo[j] && q[j] <= hi[j]) continue;
          v.detail = LimitDetail(s.robot, static_cast<int>(j), q[j]);
          break;
        }
      }
      fail(FailureReason::kJointLimits, k);
      v.collision_free = false;
    }
    ForwardKinematics(s.robot, q, &kin);
    ProximityPair hit;
    if (InCollision(s.robot, kin, &coll, &hit)) {
      if (v.reason == FailureReason::kNone) v.detail = PairName(s.robot, w.env, hit);
      fail(FailureReason::kCollision, k);
      v.collision_free = false;
      v.min_clearance_m = std::min(v.min_clearance_m, 0.0);
    } else {  // (no penetration-depth queries: FCL's EPA can abort on degenerate contacts)
      ComputeProximity(s.robot, kin, 0.2, &coll, &pairs);
      for (const ProximityPair& p : pairs) {
        v.min_clearance_m = std::min(v.min_clearance_m, p.distance);
      }
    }
    if (!winding) continue;
    ChainPoints(s.robot, kin, s.report_chain, &points);
    const double turns = topology::WindingNumber(points, axis);
    if (k > 0) {
      const double jump = std::abs(turns - w_prev);
      v.max_winding_jump_turns = std::max(v.max_winding_jump_turns, jump);
      if (c.winding_max_jump > 0.0 && jump >= c.winding_max_jump) {
        const JumpPlace place = LocateJump(s, w, dense.q.col(k - 1), dense.q.col(k));
        switch (place) {
          case JumpPlace::kThrough:
            ++v.winding_jumps.through_object;
            break;
          case JumpPlace::kBeyondEnds:
            ++v.winding_jumps.beyond_ends;
            break;
          case JumpPlace::kUnlocated:
            ++v.winding_jumps.unlocated;
            break;
        }
        const bool tunnel =
            !c.winding_tunnel_through_object_only || place != JumpPlace::kBeyondEnds;
        if (tunnel && tunnel_step < 0) tunnel_step = k;
      }
    }
    w_prev = turns;
  }
  // A winding jump means the arm passed through the pole (or off its end): name that, not the
  // collision of the states on the way through.
  if (tunnel_step >= 0 &&
      (v.reason == FailureReason::kNone || v.reason == FailureReason::kCollision)) {
    v.reason = FailureReason::kTunnelled;
    v.step = tunnel_step;
  }
  const Eigen::VectorXd q_end = path.q.col(path.num_points() - 1);
  const EndState end = CheckEndState(s, w, q_end, false, c);
  v.final_winding_turns = c.winding_closed_by_chord ? end.winding_turns : w_prev;
  v.final_writhe_total = end.writhe_total;
  v.writhe_peak_row = end.writhe_peak_row;
  v.writhe_peak_col = end.writhe_peak_col;
  v.writhe_peak_value = end.writhe_peak_value;
  if (!end.writhe_reached) fail(FailureReason::kWritheNotReached, -1);
  v.reach_error_m = end.reach_error_m;
  if (!end.reached) fail(FailureReason::kReachError, -1);
  // Through the loop: the report chain at the end against the report object's closed loop.
  if (s.report_chain >= 0 && IsClosedLoop(w.report_object_chain)) {
    ForwardKinematics(s.robot, q_end, &kin);
    ChainPoints(s.robot, kin, s.report_chain, &points);
    v.loop_checked = true;
    v.through_segment = ChainSegmentThroughLoop(points, w.report_object_chain);
    v.passed_through = v.through_segment >= 0;
  }
  if (c.through_loop && !v.passed_through) fail(FailureReason::kNotThroughLoop, -1);
  return v;
}

EndState CheckEndState(const Scenario& s, const Eigen::VectorXd& q, bool state_checks) {
  return CheckEndState(s, s.initial, q, state_checks, s.success);
}

EndState CheckEndState(const Scenario& s, const ScenarioState& w, const Eigen::VectorXd& q,
                       bool state_checks) {
  return CheckEndState(s, w, q, state_checks, s.success);
}

EndState CheckEndState(const Scenario& s, const ScenarioState& w, const Eigen::VectorXd& q,
                       bool state_checks, const SuccessCriteria& c) {
  EndState e;
  double& v = e.violation;
  if (state_checks) {
    const Eigen::VectorXd lo = LowerLimits(s.robot), hi = UpperLimits(s.robot);
    e.within_limits = !((q.array() < lo.array()) || (q.array() > hi.array())).any();
    CollisionData coll(s.robot, w.env, s.collision);
    KinematicsData kin(s.robot);
    ForwardKinematics(s.robot, q, &kin);
    e.collision_free = !InCollision(s.robot, kin, &coll);
    v += (e.within_limits ? 0.0 : 1.0) + (e.collision_free ? 0.0 : 1.0);
  }
  // Adds the relative excess of |x| over `bound` to the violation; false when the bound is missed.
  auto within = [&v](double x, double bound, bool strict) {
    if (strict ? std::abs(x) < bound : std::abs(x) <= bound) return true;
    v += bound > 0.0 ? std::abs(x) / bound : 1.0 + std::abs(x);
    return false;
  };
  Eigen::MatrixXd W;
  e.writhe_total = ReportWritheTotal(s, w, q, &W, c.writhe_closed_by_chord);
  if (W.size() > 0) {
    Eigen::Index row = 0, col = 0;
    W.cwiseAbs().maxCoeff(&row, &col);
    e.writhe_peak_row = static_cast<int>(row);
    e.writhe_peak_col = static_cast<int>(col);
    e.writhe_peak_value = W(row, col);
  }
  if (c.winding_max_jump > 0.0 || c.winding_final_below > 0.0)
    e.winding_turns = EndWinding(s, w, q, c.winding_closed_by_chord);
  if (c.writhe_total_below >= 0.0)
    e.writhe_reached = within(e.writhe_total, c.writhe_total_below, true);
  if (c.winding_final_below > 0.0)
    e.writhe_reached = within(e.winding_turns, c.winding_final_below, true) && e.writhe_reached;
  const int T = w.problem.num_steps;
  if (c.position_task >= 0) {
    const Task& task = w.problem.tasks[c.position_task];
    e.reach_error_m = (FeatureValue(s.robot, *task.feature, q) - task.target.col(T)).norm();
    e.reached = within(e.reach_error_m, c.position_tolerance, false);
  }
  if (c.box_task >= 0) {
    // The box itself (centre ± half extent): the task's margin only keeps the plan off its faces
    // (a quadratic hinge settles just outside its region when other terms pull outward).
    const FeatureSpec& f = w.tasks[c.box_task].feature;
    const auto box = MakeBoxFeature(s.robot, FindLink(s.robot, f.link.name), f.offset, f.center,
                                    f.half_extent, 0.0);
    e.reached = within(FeatureValue(s.robot, *box, q).norm(), 1e-9, false) && e.reached;
  }
  if (!std::isfinite(v)) v = std::numeric_limits<double>::max();
  return e;
}

int ChainSegmentThroughLoop(const Eigen::Matrix3Xd& chain, const Eigen::Matrix3Xd& loop) {
  if (chain.cols() < 2 || loop.cols() < 3) return -1;
  // Mean plane of the loop: centroid and Newell normal.
  const Eigen::Vector3d c = loop.rowwise().mean();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (Eigen::Index k = 0; k < loop.cols(); ++k) {
    const Eigen::Vector3d a = loop.col(k) - c;
    const Eigen::Vector3d b = loop.col((k + 1) % loop.cols()) - c;
    n += a.cross(b);
  }
  if (n.norm() < 1e-12) return -1;
  n.normalize();
  for (Eigen::Index k = 0; k + 1 < chain.cols(); ++k) {
    const double da = n.dot(chain.col(k) - c), db = n.dot(chain.col(k + 1) - c);
    if (da * db > 0.0 || da == db) continue;
    const Eigen::Vector3d x = chain.col(k) + (da / (da - db)) * (chain.col(k + 1) - chain.col(k));
    if (std::abs(topology::PlanarWinding(loop, x, n)) >= 0.5) return static_cast<int>(k);
  }
  return -1;
}

bool ChainThroughLoop(const Eigen::Matrix3Xd& chain, const Eigen::Matrix3Xd& loop) {
  return ChainSegmentThroughLoop(chain, loop) >= 0;
}

bool IsClosedLoop(const Eigen::Matrix3Xd& loop) {
  return loop.cols() > 3 && (loop.col(0) - loop.col(loop.cols() - 1)).norm() < 1e-9;
}

}  // namespace planning
