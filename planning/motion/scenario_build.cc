#include "planning/motion/internal/scenario_build.h"

#include <algorithm>
#include <stdexcept>

#include "base/json_reader.h"
#include "planning/motion/success.h"
#include "planning/robot/kinematics.h"
#include "topology/winding.h"
#include "topology/writhe.h"

namespace planning::internal {

int FindIn(const SpecName& n, int (*find)(const Robot&, const std::string&), const Robot& r) {
  return base::PrefixErrors(n.where, [&] { return find(r, n.name); });
}

Eigen::Matrix3Xd ObjectChain(const ScenarioState& w, const SpecName& object,
                             const SpecName& chain) {
  const int o =
      base::PrefixErrors(object.where, [&] { return FindObject(w.objects, object.name); });
  const int c = FindIn(chain, FindChain, w.objects.objects[o].model);
  return ObjectChainPoints(w.objects, o, c);
}

// The line through the first and last point of the feature's object chain.
topology::Axis ObjectLine(const ScenarioState& w, const FeatureSpec& f) {
  const Eigen::Matrix3Xd o = ObjectChain(w, f.object, f.object_chain);
  topology::Axis line;
  line.point = o.col(0);
  line.direction = o.col(o.cols() - 1) - o.col(0);
  return line;
}

// The feature of a task spec with the objects of state `w`.
std::unique_ptr<Feature> BuildFeature(const Scenario& s, const ScenarioState& w,
                                      const FeatureSpec& f) {
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
        return MakeJointLimitFeature(r, f.margin, f.prismatic_margin);
      case FeatureType::kJointPosition:
        return MakeJointPositionFeature(r);
      case FeatureType::kBox:
        return MakeBoxFeature(r, link(), f.offset, f.center, f.half_extent, f.margin);
      case FeatureType::kWrithe:
        return MakeWritheFeature(r, chain(), ObjectChain(w, f.object, f.object_chain), f.output,
                                 f.closed_by_chord);
      case FeatureType::kWinding: {
        if (!f.object.name.empty()) return MakeWindingFeature(r, chain(), ObjectLine(w, f));
        topology::Axis axis;
        axis.point = f.axis_point;
        axis.direction = f.axis_direction;
        return MakeWindingFeature(r, chain(), axis);
      }
      case FeatureType::kCollision:
        return MakeCollisionFeature(r, w.env, s.collision, f.margin);
      case FeatureType::kLineClearance:
        return MakeLineClearanceFeature(r, chain(), ObjectLine(w, f), f.margin);
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

namespace {

// For a writhe target's "chord_to": the total writhe between the straight segment from the
// writhe chain's first point at q0 to the final target of the named position task and the
// feature's object chain.
double ChordWrithe(const Scenario& s, const ScenarioState& w, const FeatureSpec& f,
                   const SpecName& task, const Eigen::VectorXd& q0) {
  const TaskSpec* to = nullptr;
  for (const TaskSpec& t : w.tasks) {  // the state's tasks (their targets move with objects)
    if (t.name == task.name) to = &t;
  }
  if (to == nullptr) throw std::invalid_argument(task.where + ": no task \"" + task.name + "\"");
  if (to->feature.type != FeatureType::kPosition ||
      (to->target.kind != TargetKind::kValue && to->target.kind != TargetKind::kInterpolate) ||
      (!to->target.scalar && to->target.value.size() != 3)) {
    throw std::invalid_argument(task.where + ": task \"" + task.name +
                                "\" is not a \"position\" task with a point target");
  }
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q0, &kin);
  Eigen::Matrix3Xd chain;
  ChainPoints(s.robot, kin, FindIn(f.chain, FindChain, s.robot), &chain);
  Eigen::Matrix3Xd chord(3, 2);
  // The spec's frames are resolved: the value is in world coordinates.
  const Eigen::Vector3d end = to->target.scalar ? Eigen::Vector3d::Constant(to->target.value[0])
                                                : Eigen::Vector3d(to->target.value);
  chord << chain.col(0), end;
  return topology::WritheMatrix(chord, ObjectChain(w, f.object, f.object_chain)).sum();
}

}  // namespace

// Task from its spec; target resolution needs q0 (and q̂_T for "final_pose").
Task BuildTask(const Scenario& s, const ScenarioState& w, const TaskSpec& spec,
               const Eigen::VectorXd& q0, const Eigen::VectorXd* q_final) {
  const int T = s.spec.problem.num_steps;
  Task task;
  task.name = spec.name;
  task.feature = BuildFeature(s, w, spec.feature);
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
    case TargetKind::kInterpolate: {
      Eigen::VectorXd end = value();
      if (target.chord_to) end.array() += ChordWrithe(s, w, spec.feature, *target.chord_to, q0);
      SetInterpolatedTarget(&task, FeatureValue(s.robot, *task.feature, q0), end, mid, fin, T);
      HoldFromReachAt(target.reach_at, &task);
      break;
    }
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

}  // namespace planning::internal
