#include "planning/motion/internal/start_coil.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>

#include "base/random.h"
#include "planning/collision/collision.h"
#include "planning/features/feature.h"
#include "planning/features/task.h"
#include "planning/motion/final_pose.h"
#include "planning/motion/internal/scenario_build.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"

namespace planning::internal {
namespace {

// kPlain: the continuation as it ends. kBackOff: one that ends in collision returns its last
// collision-free configuration instead (and `path` ends there). kPushOutAndBackOff: the same, and
// a `from` in collision is first pushed out of it at its own writhe (up to 100 steps).
enum class ContinueMode { kPlain, kBackOff, kPushOutAndBackOff };

// A task of the attempt to keep during a continuation: its spec (built in the continuation's
// world, target 0: a hinge such as line clearance) and the precision it has in the attempt.
struct KeptTask {
  const TaskSpec* spec;
  double precision;
};

// What a continuation steps along: the total writhe of the report pair (ReportWritheTotal), or the
// winding of the report chain about the report object's line (ReportWinding, turns).
enum class Measure { kWrithe, kWinding };

// The one-step pose-estimate problem of a continuation from q0 in `world`: the measure with target
// `value` (precision 1000), a collision hinge with `margin` (100), a joint-limit hinge (100) and
// the `kept` tasks (target 0).
MotionProblem ContinuationProblem(const Scenario& s, const ScenarioState& world,
                                  const Eigen::VectorXd& q0, double value, double margin,
                                  const std::vector<KeptTask>& kept,
                                  Measure measure = Measure::kWrithe) {
  const bool by_winding = measure == Measure::kWinding;
  MotionProblem p;
  p.robot = &s.robot;
  p.q0 = q0;
  p.num_steps = 1;
  p.dynamic = false;
  p.w_rate = 100.0;
  Task w;
  w.name = by_winding ? "winding" : "writhe";
  w.feature = by_winding ? MakeWindingFeature(s.robot, s.report_chain, ReportAxis(s, world))
                         : MakeWritheFeature(s.robot, s.report_chain, world.report_object_chain,
                                             WritheOutput::kTotal);
  SetConstantTarget(&w, Eigen::VectorXd::Constant(1, value), 1000.0, 1);
  p.tasks.push_back(std::move(w));
  Task c;
  c.name = "collision";
  c.feature = MakeCollisionFeature(s.robot, world.env, s.collision, margin);
  SetConstantTarget(&c, Eigen::VectorXd::Zero(c.feature->dim()), 100.0, 1);
  p.tasks.push_back(std::move(c));
  Task l;
  l.name = "limits";
  l.feature = MakeJointLimitFeature(s.robot, 0.05);
  SetConstantTarget(&l, Eigen::VectorXd::Zero(l.feature->dim()), 100.0, 1);
  p.tasks.push_back(std::move(l));
  for (const KeptTask& k : kept) {
    Task t;
    t.name = k.spec->name;
    t.feature = BuildFeature(s, world, k.spec->feature);
    SetConstantTarget(&t, Eigen::VectorXd::Zero(t.feature->dim()), k.precision, 1);
    p.tasks.push_back(std::move(t));
  }
  return p;
}

// Adds what the pose estimates of `p` spent through `ws` to *counts.
void AddSpent(const MotionProblem& p, const TaskWorkspace& ws, InitCounts* counts) {
  counts->units += TaskQueryCounts(p, ws);
  counts->collision_queries += CollisionQueries(p, ws);
  counts->narrow_phase_calls += NarrowPhaseCalls(p, ws);
}

// One continuation (see WritheContinuation and StartCoil) in `world` (the pole where it is), in
// steps of `step` along the measure `along` (the writhe, or for "winding_then_reach" the winding
// about the pole's line; UnwindingInit).
Eigen::VectorXd RunContinuation(const Scenario& s, const ScenarioState& world,
                                const Eigen::VectorXd& from, double target, double step,
                                double margin, ContinueMode mode,
                                std::vector<Eigen::VectorXd>* path, InitCounts* counts = nullptr,
                                const std::vector<KeptTask>& kept = {},
                                Measure along = Measure::kWrithe) {
  const bool push_out = mode == ContinueMode::kPushOutAndBackOff;
  MotionProblem p = ContinuationProblem(s, world, from, 0.0, margin, kept, along);
  TaskWorkspace ws(p);
  // The winding is read through the continuation's own winding task, so that its evaluations are
  // charged (a state query and a pair test per segment each); the writhe queries no world.
  const auto measure = [&](const Eigen::VectorXd& x) {
    if (along == Measure::kWrithe) return ReportWritheTotal(s, world, x);
    EvaluateTask(p, 0, x, false, &ws);
    return ws.y[0][0];
  };
  FinalPoseOptions fo;
  fo.alpha = 0.5;
  Eigen::VectorXd q = from;
  if (path != nullptr) path->push_back(q);
  CollisionData coll(s.robot, world.env, s.collision);
  KinematicsData kin(s.robot);
  const auto collision_free = [&](const Eigen::VectorXd& x) {
    ForwardKinematics(s.robot, x, &kin);
    return !InCollision(s.robot, kin, &coll);
  };
  const auto add_counts = [&] {
    if (counts == nullptr) return;
    AddSpent(p, ws, counts);
    counts->units += Counts(coll);
    counts->collision_queries += coll.queries;
    counts->narrow_phase_calls += coll.narrow_phase_calls;
  };
  std::optional<Eigen::VectorXd> last_free;
  size_t last_free_size = 0;           // path->size() when last_free was accepted
  const auto remember_if_free = [&] {  // only the back-off modes use it
    if (mode == ContinueMode::kPlain || !collision_free(q)) return;
    last_free = q;
    last_free_size = path != nullptr ? path->size() : 0;
  };
  remember_if_free();
  double current = measure(q);
  for (int k = 0; push_out && k < 100 && !last_free; ++k) {
    p.q0 = q;
    p.tasks[0].target.setConstant(current);
    q = EstimateFinalPose(p, fo, &ws).q;
    current = measure(q);
    if (path != nullptr) path->push_back(q);
    remember_if_free();
  }
  for (int k = 0; k < 1000 && std::abs(current - target) > 0.005; ++k) {
    const double next =
        current + std::copysign(std::min(step, std::abs(target - current)), target - current);
    p.q0 = q;
    p.tasks[0].target.setConstant(next);
    const FinalPoseResult r = EstimateFinalPose(p, fo, &ws);
    const double moved = measure(r.q);
    if (std::abs(moved - current) < 1e-4) break;  // stuck
    q = r.q;
    current = moved;
    if (path != nullptr) path->push_back(q);
    remember_if_free();
  }
  if (mode != ContinueMode::kPlain && last_free && !collision_free(q)) {
    if (path != nullptr) path->resize(last_free_size);
    add_counts();
    return *last_free;
  }
  add_counts();
  return q;
}

// The reach continuation of kUnwindingThenReach and kWindingThenReach (see UnwindingInit; the
// writhe held in both): from path->back(), each
// position task in `reach` moved in a straight line from its point there to its final target
// `goals[i]`, appending every estimate to *path.
constexpr double kReachStep = 0.05;  // m, largest target move per estimate
constexpr int kReachSettle = 5;      // estimates at the targets after the last move

void ContinueReach(const Scenario& s, const ScenarioState& world, double margin,
                   const std::vector<const TaskSpec*>& reach,
                   const std::vector<Eigen::Vector3d>& goals, const std::vector<KeptTask>& kept,
                   std::vector<Eigen::VectorXd>* path, InitCounts* counts) {
  MotionProblem p = ContinuationProblem(s, world, path->back(),
                                        ReportWritheTotal(s, world, path->back()), margin, kept);
  const size_t first_reach = p.tasks.size();
  for (const TaskSpec* spec : reach) {
    Task t;
    t.name = spec->name;
    t.feature = BuildFeature(s, world, spec->feature);
    SetConstantTarget(&t, Eigen::VectorXd::Zero(3), 1000.0, 1);
    p.tasks.push_back(std::move(t));
  }
  TaskWorkspace ws(p);
  // Where each point starts (a position task queries no world: no state query is spent).
  std::vector<Eigen::Vector3d> from;
  double longest = 0.0;
  for (size_t i = 0; i < reach.size(); ++i) {
    EvaluateTask(p, static_cast<int>(first_reach + i), p.q0, false, &ws);
    from.push_back(ws.y[first_reach + i]);
    longest = std::max(longest, (goals[i] - from[i]).norm());
  }
  FinalPoseOptions fo;
  fo.alpha = 0.5;
  const int moves = std::max(1, static_cast<int>(std::ceil(longest / kReachStep)));
  for (int k = 1; k <= moves + kReachSettle; ++k) {
    const double a = std::min(1.0, static_cast<double>(k) / moves);
    for (size_t i = 0; i < reach.size(); ++i)
      p.tasks[first_reach + i].target.colwise() = (1.0 - a) * from[i] + a * goals[i];
    p.q0 = path->back();
    path->push_back(EstimateFinalPose(p, fo, &ws).q);
  }
  if (counts != nullptr) AddSpent(p, ws, counts);
}

}  // namespace

Eigen::VectorXd WritheContinuation(const Scenario& s, const Eigen::VectorXd& from, double target,
                                   double step, double margin, std::vector<Eigen::VectorXd>* path) {
  return RunContinuation(s, s.initial, from, target, step, margin, ContinueMode::kPlain, path);
}

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

Trajectory UnwindingInit(const Scenario& s, const ScenarioState& world, const Eigen::VectorXd& q0,
                         AicoInit kind, const MotionProblem& problem, InitCounts* counts) {
  // The attempt's line-clearance and position tasks (a task switched off has precision 0).
  std::vector<KeptTask> line;
  std::vector<const TaskSpec*> reach;
  std::vector<Eigen::Vector3d> goals;
  if (problem.tasks.size() != world.tasks.size())
    throw std::logic_error("UnwindingInit: the problem has not one task per scenario task");
  for (size_t i = 0; i < problem.tasks.size(); ++i) {
    const Task& task = problem.tasks[i];
    const TaskSpec& spec = world.tasks[i];
    if (task.order != 0) continue;
    const Eigen::Index T = task.target.cols() - 1;
    if (spec.feature.type == FeatureType::kLineClearance && task.precision.maxCoeff() > 0.0)
      line.push_back({&spec, task.precision.maxCoeff()});
    if (spec.feature.type == FeatureType::kPosition && task.precision[T] > 0.0) {
      reach.push_back(&spec);
      goals.push_back(task.target.col(T));
    }
  }
  const bool by_winding = kind == AicoInit::kWindingThenReach;
  const bool then_reach = kind == AicoInit::kUnwindingThenReach || by_winding;
  if (!then_reach) line.clear();
  std::vector<Eigen::VectorXd> path;
  RunContinuation(s, world, q0, 0.0, s.spec.start.step, s.spec.start.margin, ContinueMode::kPlain,
                  &path, counts, line, by_winding ? Measure::kWinding : Measure::kWrithe);
  if (then_reach && !reach.empty())
    ContinueReach(s, world, s.spec.start.margin, reach, goals, line, &path, counts);
  Trajectory init;
  init.dt = s.spec.problem.duration / s.spec.problem.num_steps;
  init.q = ResampleByArcLength(path, s.spec.problem.num_steps + 1);
  return init;
}

bool CollisionFree(const Scenario& s, const Eigen::VectorXd& q) {
  CollisionData coll(s.robot, s.initial.env, s.collision);
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  return !InCollision(s.robot, kin, &coll);
}

// The start coil: the continuation from `from` to `target`, made a state the robot can be in. The
// collision task is a soft cost, so a continuation may end in collision; then it backs off to its
// last collision-free configuration, even if that stops it short of the angle asked, and one
// that was never collision-free (a moved pole through the robot's zero pose, which the steps need
// not leave) is run again from `from` pushed out of collision first. A continuation that ends
// collision-free is kept as it is. A short arm's continuation can stop in a local minimum of the
// writhe and collision costs well short of the angle asked (the 12-link arm on moved poles): when
// the start found collides or is more than kCoilShortBy from `target`, the continuation is run
// again from kCoilRestarts seeded perturbations of `from` (each joint uniform within
// ±kCoilRestartRad, clamped to its limits), and the end closest to `target` that is collision-free
// and inside the joint limits is kept (the continuation's limit task is soft). A start must also be
// a coil about the pole's line: beyond the ends of the report object's chain no segment may come
// within `margin` of that line (ReportLineDistanceBeyondEnds). A 30-link arm's tail can end past
// the pole's end a centimetre from its line, one small move from passing it: the winding about the
// line then jumps by a turn whatever a planner does (tuning_14 at 720°: 1.1 cm, every planner
// "tunnelled"). Such a start is restarted as one that collides is, and a restart that keeps the
// line clear is preferred; when none does, the start chosen without this rule is kept. Sets
// *collides when no collision-free start was found and *near_line when the start kept is within
// `margin` of the line beyond the ends.
constexpr double kCoilShortBy = 10.0 / 360.0;  // turns of writhe (10°)
constexpr int kCoilRestarts = 32;
constexpr double kCoilRestartRad = 1.0;

Eigen::VectorXd StartCoil(const Scenario& s, const Eigen::VectorXd& from, double target,
                          double step, double margin, bool* collides, bool* near_line) {
  // kBackOff returns the plain continuation whenever that ends collision-free.
  Eigen::VectorXd q =
      RunContinuation(s, s.initial, from, target, step, margin, ContinueMode::kBackOff, nullptr);
  bool free = CollisionFree(s, q);
  if (!free) {
    q = RunContinuation(s, s.initial, from, target, step, margin, ContinueMode::kPushOutAndBackOff,
                        nullptr);
    free = CollisionFree(s, q);
  }
  *collides = !free;
  const Eigen::VectorXd lower = LowerLimits(s.robot);
  const Eigen::VectorXd upper = UpperLimits(s.robot);
  const auto inside = [&](const Eigen::VectorXd& x) {
    return (x.array() >= lower.array()).all() && (x.array() <= upper.array()).all();
  };
  const auto clear_of_line = [&](const Eigen::VectorXd& x) {
    return ReportLineDistanceBeyondEnds(s, x) >= margin;
  };
  // The best start clear of the line, and the best start as chosen without that rule (restarts
  // stop once it is within kCoilShortBy), kept when no start is clear.
  const double infinity = std::numeric_limits<double>::infinity();
  const double first =
      *collides || !inside(q) ? infinity : std::abs(ReportWritheTotal(s, q) - target);
  double best = clear_of_line(q) ? first : infinity;
  double best_any = first;
  Eigen::VectorXd any = q;
  std::mt19937 rng(1);
  for (int k = 0; k < kCoilRestarts && best > kCoilShortBy; ++k) {
    Eigen::VectorXd perturbed = from;
    for (Eigen::Index i = 0; i < perturbed.size(); ++i) {
      perturbed[i] =
          std::clamp(perturbed[i] + kCoilRestartRad * (2.0 * base::UniformUnit(&rng) - 1.0),
                     lower[i], upper[i]);
    }
    const Eigen::VectorXd x = RunContinuation(s, s.initial, perturbed, target, step, margin,
                                              ContinueMode::kPushOutAndBackOff, nullptr);
    const double error = std::abs(ReportWritheTotal(s, x) - target);
    if (!inside(x) || !CollisionFree(s, x)) continue;
    if (best_any > kCoilShortBy && error < best_any) {
      best_any = error;
      any = x;
    }
    if (error < best && clear_of_line(x)) {
      best = error;
      q = x;
      *collides = false;
    }
  }
  if (best == infinity && best_any < infinity) {  // no clear start: the best one as before
    q = any;
    *collides = false;
  }
  *near_line = !clear_of_line(q);
  return q;
}

}  // namespace planning::internal
