#include "planning/motion/scenario.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/assets.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/pose.h"
#include "planning/robot/robot_io.h"
#include "planning/robot/srdf.h"
#include "topology/winding.h"
#include "topology/writhe.h"

namespace planning {
namespace {

int FindIn(const SpecName& n, int (*find)(const Robot&, const std::string&), const Robot& r) {
  return base::PrefixErrors(n.where, [&] { return find(r, n.name); });
}

Eigen::Matrix3Xd ObjectChain(const Scenario& s, const SpecName& object, const SpecName& chain) {
  const int o = base::PrefixErrors(object.where, [&] { return FindObject(s.objects, object.name); });
  const int c = FindIn(chain, FindChain, s.objects.objects[o].model);
  return ObjectChainPoints(s.objects, o, c);
}

// The line through the first and last point of the feature's object chain.
topology::Axis ObjectLine(const Scenario& s, const FeatureSpec& f) {
  const Eigen::Matrix3Xd o = ObjectChain(s, f.object, f.object_chain);
  topology::Axis line;
  line.point = o.col(0);
  line.direction = o.col(o.cols() - 1) - o.col(0);
  return line;
}

std::unique_ptr<Feature> BuildFeature(const Scenario& s, const FeatureSpec& f) {
  const Robot& r = s.robot;
  auto link = [&] { return FindIn(f.link, FindLink, r); };
  auto chain = [&] { return FindIn(f.chain, FindChain, r); };
  return base::PrefixErrors(f.where, [&]() -> std::unique_ptr<Feature> {
    switch (f.type) {
      case FeatureType::kPosition:
        return MakePositionFeature(r, link(), f.offset);
      case FeatureType::kAxisAlignment:
        return MakeAxisAlignmentFeature(r, link(), f.axis, f.direction);
      case FeatureType::kJointLimits:
        return MakeJointLimitFeature(r, f.margin);
      case FeatureType::kJointPosition:
        return MakeJointPositionFeature(r);
      case FeatureType::kBox:
        return MakeBoxFeature(r, link(), f.offset, f.center, f.half_extent, f.margin);
      case FeatureType::kWrithe:
        return MakeWritheFeature(r, chain(), ObjectChain(s, f.object, f.object_chain), f.output);
      case FeatureType::kWinding: {
        if (!f.object.name.empty()) return MakeWindingFeature(r, chain(), ObjectLine(s, f));
        topology::Axis axis;
        axis.point = f.axis_point;
        axis.direction = f.axis_direction;
        return MakeWindingFeature(r, chain(), axis);
      }
      case FeatureType::kCollision:
        return MakeCollisionFeature(r, s.env, s.collision, f.margin);
      case FeatureType::kLineClearance:
        return MakeLineClearanceFeature(r, chain(), ObjectLine(s, f), f.margin);
    }
    throw std::invalid_argument("unknown feature type");
  });
}

// A linear target y*_t = y*_0 + (t/T)(y*_T − y*_0) (task->target, T+1 columns) re-timed to reach
// y*_T at t = reach_at·T and hold it after: y*_t = y*_0 + min(1, t/(reach_at·T))(y*_T − y*_0).
void HoldFromReachAt(double reach_at, Task* task) {
  if (reach_at >= 1.0) return;
  const Eigen::Index T = task->target.cols() - 1;
  const Eigen::VectorXd y0 = task->target.col(0), yT = task->target.col(T);
  for (Eigen::Index t = 0; t <= T; ++t) {
    const double s = std::min(1.0, static_cast<double>(t) / (reach_at * static_cast<double>(T)));
    task->target.col(t) = (1.0 - s) * y0 + s * yT;
  }
}

// Task from its spec; target resolution needs q0 (and q̂_T for "final_pose").
Task BuildTask(const Scenario& s, const TaskSpec& spec, const Eigen::VectorXd& q0,
               const Eigen::VectorXd* q_final) {
  const int T = s.spec.problem.num_steps;
  Task task;
  task.name = spec.name;
  task.feature = BuildFeature(s, spec.feature);
  task.order = spec.order;
  task.between = spec.between;
  task.max_jump = spec.max_jump;
  const double mid = spec.precision, fin = spec.final_precision;
  const int dim = task.feature->dim();
  const TargetSpec& target = spec.target;
  auto value = [&]() -> Eigen::VectorXd {
    if (target.scalar) return Eigen::VectorXd::Constant(dim, target.value[0]);
    if (target.value.size() != dim) {
      throw std::invalid_argument(target.value_where + ": expected " + std::to_string(dim) +
                                  " numbers, got " + std::to_string(target.value.size()));
    }
    return target.value;
  };
  switch (target.kind) {
    case TargetKind::kZero:
    case TargetKind::kValue:
      SetConstantTarget(
          &task, target.kind == TargetKind::kZero ? Eigen::VectorXd::Zero(dim) : value(), mid, T);
      task.precision[T] = fin;
      break;
    case TargetKind::kInterpolate:
      SetInterpolatedTarget(&task, FeatureValue(s.robot, *task.feature, q0), value(), mid, fin, T);
      HoldFromReachAt(target.reach_at, &task);
      break;
    case TargetKind::kFinalPose:
      if (q_final == nullptr) {
        throw std::invalid_argument(target.where +
                                    ": \"final_pose\" targets cannot be used by the final-pose "
                                    "tasks");
      }
      SetInterpolatedTarget(&task, FeatureValue(s.robot, *task.feature, q0),
                            FeatureValue(s.robot, *task.feature, *q_final), mid, fin, T);
      HoldFromReachAt(target.reach_at, &task);
      break;
    case TargetKind::kUnwinding:
      if (s.unwinding.cols() != T + 1) {
        throw std::invalid_argument(target.where + ": \"unwinding\" targets need a coil start");
      }
      SetConstantTarget(&task, Eigen::VectorXd::Zero(dim), mid, T);
      task.precision[T] = fin;
      for (int t = 0; t <= T; ++t) {
        task.target.col(t) = FeatureValue(s.robot, *task.feature, s.unwinding.col(t));
      }
      break;
  }
  if (spec.final_steps > T) {
    throw std::invalid_argument(spec.final_steps_where + ": " + std::to_string(spec.final_steps) +
                                " final steps, but the problem has T = " + std::to_string(T));
  }
  task.precision.tail(spec.final_steps).setConstant(fin);
  return task;
}

// Writhe continuation (see scenario.h): from q toward total writhe `target` in steps.
// Every accepted configuration (from included) is appended to `path` if not null.
Eigen::VectorXd WritheContinuation(const Scenario& s, const Eigen::VectorXd& from, double target,
                                   double step, double margin,
                                   std::vector<Eigen::VectorXd>* path = nullptr) {
  MotionProblem p;
  p.robot = &s.robot;
  p.q0 = from;
  p.num_steps = 1;
  p.dynamic = false;
  p.w_rate = 100.0;
  Task w;
  w.name = "writhe";
  w.feature =
      MakeWritheFeature(s.robot, s.report_chain, s.report_object_chain, WritheOutput::kTotal);
  SetConstantTarget(&w, Eigen::VectorXd::Zero(1), 1000.0, 1);
  p.tasks.push_back(std::move(w));
  Task c;
  c.name = "collision";
  c.feature = MakeCollisionFeature(s.robot, s.env, s.collision, margin);
  SetConstantTarget(&c, Eigen::VectorXd::Zero(c.feature->dim()), 100.0, 1);
  p.tasks.push_back(std::move(c));
  Task l;
  l.name = "limits";
  l.feature = MakeJointLimitFeature(s.robot, 0.05);
  SetConstantTarget(&l, Eigen::VectorXd::Zero(l.feature->dim()), 100.0, 1);
  p.tasks.push_back(std::move(l));
  TaskWorkspace ws(p);
  FinalPoseOptions fo;
  fo.alpha = 0.5;
  Eigen::VectorXd q = from;
  if (path != nullptr) path->push_back(q);
  double current = ReportWritheTotal(s, q);
  for (int k = 0; k < 1000 && std::abs(current - target) > 0.005; ++k) {
    const double next =
        current + std::copysign(std::min(step, std::abs(target - current)), target - current);
    p.q0 = q;
    p.tasks[0].target.setConstant(next);
    const FinalPoseResult r = EstimateFinalPose(p, fo, &ws);
    const double moved = ReportWritheTotal(s, r.q);
    if (std::abs(moved - current) < 1e-4) break;  // stuck
    q = r.q;
    current = moved;
    if (path != nullptr) path->push_back(q);
  }
  return q;
}

// `path` (at least one configuration) resampled at num_points equally spaced joint-space arc
// lengths (linear between its configurations): n × num_points.
Eigen::MatrixXd ResampleByArcLength(const std::vector<Eigen::VectorXd>& path, int num_points) {
  std::vector<double> length(path.size(), 0.0);
  for (size_t k = 1; k < path.size(); ++k)
    length[k] = length[k - 1] + (path[k] - path[k - 1]).norm();
  Eigen::MatrixXd out(path[0].size(), num_points);
  size_t k = 0;
  for (int t = 0; t < num_points; ++t) {
    const double at = num_points > 1 ? length.back() * t / (num_points - 1) : 0.0;
    while (k + 2 < path.size() && length[k + 1] < at) ++k;
    if (path.size() == 1 || length[k + 1] <= length[k]) {
      out.col(t) = path[std::min(k + 1, path.size() - 1)];
      continue;
    }
    const double a = std::clamp((at - length[k]) / (length[k + 1] - length[k]), 0.0, 1.0);
    out.col(t) = (1.0 - a) * path[k] + a * path[k + 1];
  }
  return out;
}

bool UsesUnwinding(const ScenarioSpec& spec) {
  for (const TaskSpec& t : spec.tasks) {
    if (t.target.kind == TargetKind::kUnwinding) return true;
  }
  return false;
}

struct StartPose {
  Eigen::VectorXd q0;
  Eigen::VectorXd unwrapped;               // coil start only: the coil continued to writhe 0
  std::vector<Eigen::VectorXd> unwinding;  // coil start, "unwinding" targets: q0 continued to 0
};

// The start configuration: given, zero, or the start coil (see scenario.h).
StartPose ResolveStart(const Scenario& s, const std::optional<double>& wrap_override) {
  const StartSpec& start = s.spec.start;
  const int n = num_dofs(s.robot);
  StartPose out;
  switch (start.kind) {
    case StartKind::kZero:
      out.q0 = Eigen::VectorXd::Zero(n);
      break;
    case StartKind::kPose:  // SetUpScenario turned it into kQ
    case StartKind::kQ:
      if (start.q.size() != n) {
        throw std::invalid_argument(start.where + ": expected " + std::to_string(n) +
                                    " numbers, got " + std::to_string(start.q.size()));
      }
      out.q0 = start.q;
      break;
    case StartKind::kCoil: {
      const double wrap = wrap_override ? *wrap_override : start.wrap_deg;
      if (!(wrap >= 0.0 && wrap <= 2000.0)) {
        throw std::invalid_argument(start.where + ": wrap_deg must be in [0, 2000]");
      }
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
      const double sign = ReportWritheTotal(s, zero) < 0 ? -1.0 : 1.0;
      out.q0 = WritheContinuation(s, zero, sign * wrap / 360.0, start.step, start.margin);
      out.unwrapped = WritheContinuation(s, zero, 0.0, start.step, start.margin);
      if (UsesUnwinding(s.spec))
        WritheContinuation(s, out.q0, 0.0, start.step, start.margin, &out.unwinding);
      break;
    }
  }
  return out;
}

// The goal q̂_T: the final-pose estimate over the listed tasks (their targets at T), or q0; when
// it misses the end conditions, the multi-start search (see scenario.h). Needs s.problem (its
// position and box targets) and s.success.
Eigen::VectorXd EstimateGoal(const Scenario& s, const StartPose& start) {
  const FinalPoseSpec& fps = s.spec.final_pose;
  if (fps.tasks.empty()) return start.q0;
  MotionProblem fp;
  fp.robot = &s.robot;
  fp.q0 = start.q0;
  fp.num_steps = s.spec.problem.num_steps;
  fp.duration = s.spec.problem.duration;
  fp.dynamic = false;  // the kinematic prior N(q0, T W⁻¹)
  fp.w_rate = s.spec.problem.w_rate;
  for (const SpecName& name : fps.tasks) {
    bool found = false;
    for (const TaskSpec& t : s.spec.tasks) {
      if (t.name != name.name) continue;
      fp.tasks.push_back(BuildTask(s, t, start.q0, nullptr));
      found = true;
    }
    if (!found) throw std::invalid_argument(name.where + ": no task named '" + name.name + "'");
  }
  Eigen::VectorXd init = start.q0;
  if (fps.init == FinalPoseInit::kUnwrapped) init = start.unwrapped;
  if (fps.init == FinalPoseInit::kQ) {
    if (fps.init_q.size() != start.q0.size()) {
      throw std::invalid_argument(fps.init_where + ": expected " + std::to_string(start.q0.size()) +
                                  " numbers, got " + std::to_string(fps.init_q.size()));
    }
    init = fps.init_q;
  }
  TaskWorkspace ws(fp);
  std::vector<Eigen::VectorXd> inits = {init};
  if (init != start.q0) inits.push_back(start.q0);
  const auto violation = [&s](const Eigen::VectorXd& q) {
    return CheckEndState(s, q, true).violation;
  };
  FinalPoseSearchResult best = SearchFinalPose(fp, fps.options, {}, &ws, inits, violation);
  // Further rounds, from the best so far with wider perturbations, leave terms that can fight the
  // reach to the end-condition check: first the collision hinge (its margin keeps the links apart
  // further than collision-free needs), then also the writhe term.
  FinalPoseSearch wide;
  wide.spread = 1.0;
  wide.random_starts = 16;
  for (const char* drop : {"collision", "writhe"}) {
    if (best.violation == 0.0) break;
    std::erase_if(fp.tasks, [drop](const Task& t) { return t.feature->name() == drop; });
    TaskWorkspace fewer(fp);
    std::vector<Eigen::VectorXd> from = {best.best.q};
    from.insert(from.end(), inits.begin(), inits.end());
    FinalPoseSearchResult r = SearchFinalPose(fp, fps.options, wide, &fewer, from, violation);
    if (r.violation < best.violation) best = std::move(r);
  }
  return best.best.q;
}

int TaskIndex(const Scenario& s, const SpecName& n) {
  for (size_t i = 0; i < s.spec.tasks.size(); ++i) {
    if (s.spec.tasks[i].name == n.name) return static_cast<int>(i);
  }
  std::vector<std::string> names;
  for (const TaskSpec& t : s.spec.tasks) names.push_back(t.name);
  throw std::invalid_argument(n.where + ": no task named '" + n.name + "'" +
                              base::DidYouMean(n.name, names));
}

void LoadObjects(Scenario* s) {
  for (const ObjectSpec& o : s->spec.objects) {
    Robot model = base::PrefixErrors(o.where + ".urdf", [&] { return LoadRobot(o.urdf); });
    const Eigen::Isometry3d pose = PoseFromXyzRpy(o.xyz, o.rpy);
    base::PrefixErrors(o.where, [&] { AddObject(model, pose, o.name, &s->objects); });
    if (!o.collide) continue;
    if (!o.capsule_chain) {
      AddObject(model, pose, o.name, &s->env);
      continue;
    }
    const int obj = static_cast<int>(s->objects.objects.size()) - 1;
    const int chain = FindIn(*o.capsule_chain, FindChain, model);
    const Eigen::Matrix3Xd pts = ObjectChainPoints(s->objects, obj, chain);
    for (Eigen::Index k = 0; k + 1 < pts.cols(); ++k) {
      const Eigen::Vector3d a = pts.col(k), b = pts.col(k + 1);
      Geometry g;
      g.kind = Geometry::Kind::kCapsule;
      g.size = Eigen::Vector3d(o.capsule_radius, (b - a).norm(), 0.0);
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = 0.5 * (a + b);
      T.linear() =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), b - a).toRotationMatrix();
      const std::string part = o.name + "#" + std::to_string(k);
      AddObject(MakePrimitiveObject(part, g), T, part, &s->env);
    }
  }
}

void SetUpCollision(Scenario* s) {
  const CollisionSpec& c = s->spec.collision;
  s->collision.self_collision = c.self;
  s->collision.analytic_capsules = c.analytic_capsules;
  s->collision.disabled_pairs = c.disabled_pairs;
  // Every pair of links whose names start with prefixes of the same group is not checked.
  for (const std::vector<std::string>& prefixes : c.disabled_groups) {
    auto member = [&](const std::string& name) {
      for (const std::string& p : prefixes) {
        if (name.rfind(p, 0) == 0) return true;
      }
      return false;
    };
    const auto& links = s->robot.links;
    for (size_t a = 0; a < links.size(); ++a) {
      for (size_t b = a + 1; b < links.size(); ++b) {
        if (member(links[a].name) && member(links[b].name)) {
          s->collision.disabled_pairs.emplace_back(links[a].name, links[b].name);
        }
      }
    }
  }
  // Validate the options once (unknown link names throw here, with the JSON path).
  if (!c.where.empty())
    base::PrefixErrors(c.where, [&] { CollisionData check(s->robot, s->env, s->collision); });
}

}  // namespace

Eigen::VectorXd FeatureValue(const Robot& robot, const Feature& f, const Eigen::VectorXd& q) {
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  auto data = f.CreateData(robot);
  Eigen::VectorXd y(f.dim());
  f.Eval(robot, kin, data.get(), y, nullptr);
  return y;
}

double ReportWritheTotal(const Scenario& s, const Eigen::VectorXd& q, Eigen::MatrixXd* matrix) {
  if (s.report_chain < 0) {
    if (matrix != nullptr) matrix->resize(0, 0);
    return 0.0;
  }
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  Eigen::Matrix3Xd P;
  ChainPoints(s.robot, kin, s.report_chain, &P);
  const Eigen::MatrixXd W = topology::WritheMatrix(P, s.report_object_chain);
  if (matrix != nullptr) *matrix = W;
  return W.sum();
}

double ReportWinding(const Scenario& s, const Eigen::VectorXd& q) {
  if (s.report_chain < 0) return 0.0;
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  Eigen::Matrix3Xd P;
  ChainPoints(s.robot, kin, s.report_chain, &P);
  return topology::WindingNumber(P, ReportAxis(s));
}

topology::Axis ReportAxis(const Scenario& s) {
  const Eigen::Matrix3Xd& O = s.report_object_chain;
  if (s.report_chain < 0 || O.cols() < 2) throw std::invalid_argument("ReportAxis: no report pair");
  topology::Axis axis;
  axis.point = O.col(0);
  axis.direction = O.col(O.cols() - 1) - O.col(0);
  return axis;
}

EndState CheckEndState(const Scenario& s, const Eigen::VectorXd& q, bool state_checks) {
  const SuccessCriteria& c = s.success;
  EndState e;
  double& v = e.violation;
  if (state_checks) {
    const Eigen::VectorXd lo = LowerLimits(s.robot), hi = UpperLimits(s.robot);
    e.within_limits = !((q.array() < lo.array()) || (q.array() > hi.array())).any();
    CollisionData coll(s.robot, s.env, s.collision);
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
  e.writhe_total = ReportWritheTotal(s, q, &W);
  if (W.size() > 0) {
    Eigen::Index row = 0, col = 0;
    W.cwiseAbs().maxCoeff(&row, &col);
    e.writhe_peak_row = static_cast<int>(row);
    e.writhe_peak_col = static_cast<int>(col);
    e.writhe_peak_value = W(row, col);
  }
  if (c.winding_max_jump > 0.0 || c.winding_final_below > 0.0)
    e.winding_turns = ReportWinding(s, q);
  if (c.writhe_total_below >= 0.0)
    e.writhe_reached = within(e.writhe_total, c.writhe_total_below, true);
  if (c.winding_final_below > 0.0)
    e.writhe_reached = within(e.winding_turns, c.winding_final_below, true) && e.writhe_reached;
  const int T = s.problem.num_steps;
  if (c.position_task >= 0) {
    const Task& task = s.problem.tasks[c.position_task];
    e.reach_error_m = (FeatureValue(s.robot, *task.feature, q) - task.target.col(T)).norm();
    e.reached = within(e.reach_error_m, c.position_tolerance, false);
  }
  if (c.box_task >= 0) {
    // The box itself (centre ± half extent): the task's margin only keeps the plan off its faces
    // (a quadratic hinge settles just outside its region when other terms pull outward).
    const FeatureSpec& f = s.spec.tasks[c.box_task].feature;
    const auto box = MakeBoxFeature(s.robot, FindLink(s.robot, f.link.name), f.offset, f.center,
                                    f.half_extent, 0.0);
    e.reached = within(FeatureValue(s.robot, *box, q).norm(), 1e-9, false) && e.reached;
  }
  if (!std::isfinite(v)) v = std::numeric_limits<double>::max();
  return e;
}

MotionProblem AttemptProblem(const Scenario& s, int k) {
  if (k < 0 || k >= static_cast<int>(s.aico_attempts.size())) {
    throw std::invalid_argument("AttemptProblem: no AICO attempt " + std::to_string(k));
  }
  const ProblemSpec& ps = s.spec.problem;
  MotionProblem p;
  p.robot = &s.robot;
  p.q0 = s.problem.q0;  // the resolved start
  p.num_steps = ps.num_steps;
  p.duration = ps.duration;
  p.dynamic = ps.dynamic;
  p.h_rate = ps.h_rate;
  p.w_rate = ps.w_rate;
  p.q_rate = ps.q_rate;
  const Eigen::VectorXd& scale = s.aico_attempts[k].precision_scale;
  for (size_t i = 0; i < s.spec.tasks.size(); ++i) {
    p.tasks.push_back(BuildTask(s, s.spec.tasks[i], p.q0, &s.goal_q));
    p.tasks.back().precision *= scale[static_cast<Eigen::Index>(i)];
  }
  base::PrefixErrors(s.source, [&] { ValidateProblem(p); });
  return p;
}

AicoOptions AttemptOptions(const Scenario& s, int k) {
  AicoOptions o = s.aico;
  o.max_iterations = s.aico_attempts.at(k).max_iterations;
  return o;
}

ResolvedPoses ResolvedPosesOf(const Scenario& s) { return {s.problem.q0, s.unwinding, s.goal_q}; }

namespace {

void CheckResolved(const ResolvedPoses& r, const Scenario& s) {
  const Eigen::Index n = num_dofs(s.robot);
  const auto check = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("resolved: " + what);
  };
  check(r.q0.size() == n && r.q0.allFinite(),
        "q0: expected " + std::to_string(n) + " finite numbers");
  check(r.goal_q.size() == n && r.goal_q.allFinite(),
        "goal_q: expected " + std::to_string(n) + " finite numbers");
  const bool wants = UsesUnwinding(s.spec) && s.spec.start.kind == StartKind::kCoil;
  const Eigen::Index cols = s.spec.problem.num_steps + 1;
  check(wants ? (r.unwinding.rows() == n && r.unwinding.cols() == cols && r.unwinding.allFinite())
              : r.unwinding.size() == 0,
        wants ? "unwinding: expected " + std::to_string(n) + " x " + std::to_string(cols) +
                    " finite numbers"
              : "unwinding: expected none (the scenario has no unwinding target)");
}

}  // namespace

std::unique_ptr<Scenario> SetUpScenario(ScenarioSpec spec,
                                        const std::optional<double>& start_wrap_deg,
                                        const ResolvedPoses* resolved) {
  auto s = std::make_unique<Scenario>();
  s->spec = std::move(spec);
  const ScenarioSpec& sp = s->spec;
  s->name = sp.name;
  s->source = sp.source;
  RobotLoadOptions load;
  load.package_paths = sp.package_paths;
  s->robot = base::PrefixErrors(sp.source + ": robot", [&] { return LoadRobot(sp.robot, load); });
  const std::string srdf_path = sp.srdf.empty() ? FindSrdf(sp.robot) : sp.srdf;
  std::optional<Srdf> srdf;
  if (!srdf_path.empty()) {
    srdf = LoadSrdf(srdf_path);
    CheckSrdf(*srdf, s->robot);
  }
  if (sp.start.kind == StartKind::kPose) {
    if (!srdf) throw std::invalid_argument(sp.start.where + ": a pose start needs an SRDF");
    s->spec.start.q =
        base::PrefixErrors(sp.start.where, [&] { return NamedPose(s->robot, *srdf, sp.start.pose); });
    s->spec.start.kind = StartKind::kQ;
  }
  LoadObjects(s.get());
  for (const ChainDescription& c : sp.robot_chains) {
    s->robot.chains.push_back(ResolveChain(c, s->robot));
  }
  SetUpCollision(s.get());
  if (srdf) {
    for (const auto& pair : DisabledPairs(*srdf)) s->collision.disabled_pairs.push_back(pair);
  }
  if (sp.writhe_report) {
    s->report_chain = FindIn(sp.writhe_report->chain, FindChain, s->robot);
    s->report_object_chain =
        ObjectChain(*s, sp.writhe_report->object, sp.writhe_report->object_chain);
  }

  StartPose start;
  if (resolved != nullptr) {
    CheckResolved(*resolved, *s);
    start.q0 = resolved->q0;
    s->unwinding = resolved->unwinding;
  } else {
    start = ResolveStart(*s, start_wrap_deg);
    if (!start.unwinding.empty())
      s->unwinding = ResampleByArcLength(start.unwinding, sp.problem.num_steps + 1);
  }
  s->problem.q0 = start.q0;
  s->start_wrap_deg = 360.0 * std::abs(ReportWritheTotal(*s, start.q0));

  s->aico = sp.aico;
  s->stop_when_solved = sp.aico_stop_when_solved;
  s->rrt = sp.rrt;
  s->check_resolution = sp.check_resolution;
  for (const AicoAttemptSpec& a : sp.aico_attempts) {
    AicoAttempt attempt;
    attempt.max_iterations = a.max_iterations;
    attempt.precision_scale = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(sp.tasks.size()));
    for (const auto& [task, factor] : a.precision_scale)
      attempt.precision_scale[TaskIndex(*s, task)] *= factor;
    s->aico_attempts.push_back(attempt);
  }

  const SuccessSpec& su = sp.success;
  s->success.writhe_total_below = su.writhe_total_below;
  if (su.position_task) s->success.position_task = TaskIndex(*s, *su.position_task);
  s->success.position_tolerance = su.position_tolerance;
  if (su.box_task) s->success.box_task = TaskIndex(*s, *su.box_task);
  if (!su.winding_where.empty() && s->report_chain < 0) {
    throw std::invalid_argument(su.winding_where + ": the winding criterion needs writhe_report");
  }
  s->success.winding_max_jump = su.winding_max_jump;
  s->success.winding_final_below = su.winding_final_below;

  // The goal's end conditions read the position/box targets of a problem built with goal q0.
  s->goal_q = start.q0;
  s->problem = AttemptProblem(*s, 0);
  s->goal_q = resolved != nullptr ? resolved->goal_q : EstimateGoal(*s, start);
  s->problem = AttemptProblem(*s, 0);
  return s;
}

std::vector<std::string> ObjectNames(const Scenario& s) {
  std::vector<std::string> names;
  for (const ObjectSpec& o : s.spec.objects) names.push_back(o.name);
  return names;
}

void RebuildTaskFeatures(const Scenario& s, MotionProblem* problem) {
  if (problem->tasks.size() != s.spec.tasks.size()) {
    throw std::invalid_argument("RebuildTaskFeatures: the problem has " +
                                std::to_string(problem->tasks.size()) + " tasks, the scenario " +
                                std::to_string(s.spec.tasks.size()));
  }
  for (size_t i = 0; i < problem->tasks.size(); ++i) {
    problem->tasks[i].feature = BuildFeature(s, s.spec.tasks[i].feature);
  }
}

void MoveObject(Scenario* s, const std::string& name, const Eigen::Vector3d& position) {
  size_t spec_index = s->spec.objects.size();
  for (size_t i = 0; i < s->spec.objects.size(); ++i) {
    if (s->spec.objects[i].name == name) spec_index = i;
  }
  if (spec_index == s->spec.objects.size()) {
    std::string list;
    for (const std::string& n : ObjectNames(*s)) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown object '" + name +
                                "' (objects: " + (list.empty() ? "none" : list) + ")");
  }
  if (!position.allFinite()) throw std::invalid_argument("MoveObject: non-finite position");
  PlacedObject& placed = s->objects.objects[FindObject(s->objects, name)];
  const Eigen::Vector3d delta = position - placed.world_from_object.translation();
  placed.world_from_object.translation() = position;
  for (PlacedObject& e : s->env.objects) {
    if (e.name == name || e.name.rfind(name + "#", 0) == 0) e.world_from_object.pretranslate(delta);
  }
  s->spec.objects[spec_index].xyz = position;
  if (s->spec.writhe_report && s->spec.writhe_report->object.name == name) {
    s->report_object_chain =
        ObjectChain(*s, s->spec.writhe_report->object, s->spec.writhe_report->object_chain);
  }
  RebuildTaskFeatures(*s, &s->problem);
}

std::unique_ptr<Scenario> LoadScenario(const std::string& path,
                                       const ScenarioOverrides& overrides) {
  ScenarioSpec spec = ParseScenarioSpec(path, overrides.search_roots);
  spec.package_paths.insert(spec.package_paths.begin(), overrides.package_paths.begin(),
                            overrides.package_paths.end());
  if (!overrides.srdf.empty()) spec.srdf = overrides.srdf;
  if (overrides.stop_when_solved) spec.aico_stop_when_solved = *overrides.stop_when_solved;
  return SetUpScenario(std::move(spec), overrides.start_wrap_deg);
}

std::unique_ptr<Scenario> LoadScenarioArg(const std::string& arg, ScenarioOverrides overrides) {
  overrides.search_roots = {base::AssetRoot()};
  return LoadScenario(base::ResolveScenarioPath(arg), overrides);
}

}  // namespace planning
