#include "planning/motion/replan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <optional>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <string>

#include "planning/motion/success.h"
#include "planning/robot/kinematics.h"
#include "base/file_read.h"
#include "base/numbers.h"
#include "topology/winding.h"

namespace planning {
namespace {

// CPU time of the calling thread, ms.
double ThreadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double WallMs() {
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// "(objects: a, b)" (or another word than "objects").
std::string ObjectList(const std::vector<std::string>& names, const char* what = "objects") {
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return std::string("(") + what + ": " + (list.empty() ? "none" : list) + ")";
}

// The window problem at offset g: targets and precisions of `base` shifted (see replan.h).
void ShiftTargets(const MotionProblem& base, int g, MotionProblem* window) {
  const int T = base.num_steps;
  for (size_t i = 0; i < base.tasks.size(); ++i) {
    const Task& from = base.tasks[i];
    Task& to = window->tasks[i];
    for (int j = 0; j <= T; ++j) {
      const int src = std::min(g + j, T);
      to.target.col(j) = from.target.col(src);
      to.precision[j] = from.precision[src];
    }
  }
}

}  // namespace

ObjectPath ReadObjectPath(const std::string& path) {
  std::istringstream in(base::ReadFileBounded(path, "object path"));
  in.imbue(std::locale::classic());  // "0.5" whatever the global locale
  ObjectPath out;
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string text = Trim(line);
    if (text.empty()) continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (!header) {
      std::string h;
      for (char c : text) {
        if (c != ' ' && c != '\t') h += c;
      }
      if (h != "t,x,y,z") {
        throw std::invalid_argument(where + "expected the header 't,x,y,z', got '" + text + "'");
      }
      header = true;
      continue;
    }
    if (text.back() == ',')
      throw std::invalid_argument(where + "empty value at the end of the row");
    std::vector<double> v;
    std::stringstream ss(text);
    ss.imbue(std::locale::classic());  // "0.5" whatever the global locale
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      const std::string c = Trim(cell);
      double value = 0.0;
      switch (base::ClassifyNumber(c, &value)) {
        case base::NumberKind::kFinite:
          break;
        case base::NumberKind::kNonFinite:
          throw std::invalid_argument(where + "non-finite value '" + c + "'");
        case base::NumberKind::kNotANumber:
          throw std::invalid_argument(where + "'" + c + "' is not a number");
      }
      v.push_back(value);
    }
    if (v.size() != 4) {
      throw std::invalid_argument(where + "expected 4 values t,x,y,z, got " +
                                  std::to_string(v.size()));
    }
    for (double x : v) {
      if (!std::isfinite(x)) throw std::invalid_argument(where + "non-finite value");
    }
    if (!out.t.empty() && !(v[0] > out.t.back())) {
      std::ostringstream msg;
      msg.imbue(std::locale::classic());  // "0.5" whatever the global locale
      msg << where << "time " << v[0] << " is not greater than the previous time " << out.t.back();
      throw std::invalid_argument(msg.str());
    }
    out.t.push_back(v[0]);
    out.p.emplace_back(v[1], v[2], v[3]);
  }
  if (!header) throw std::invalid_argument(path + ": empty file (expected the header 't,x,y,z')");
  if (out.t.empty()) throw std::invalid_argument(path + ": no samples after the header");
  return out;
}

Eigen::Vector3d ObjectPositionAt(const ObjectPath& path, double t) {
  if (path.t.empty()) throw std::invalid_argument("ObjectPositionAt: empty path");
  if (t <= path.t.front()) return path.p.front();
  if (t >= path.t.back()) return path.p.back();
  const size_t k = static_cast<size_t>(std::upper_bound(path.t.begin(), path.t.end(), t) -
                                       path.t.begin());  // t[k-1] <= t < t[k]
  const double a = (t - path.t[k - 1]) / (path.t[k] - path.t[k - 1]);
  return (1.0 - a) * path.p[k - 1] + a * path.p[k];
}

namespace {

// The world-space point of task i (see replan.h), if it has one.
std::optional<Eigen::Vector3d> TaskPoint(const ScenarioState& w, size_t i) {
  const FeatureSpec& f = w.tasks[i].feature;
  switch (f.type) {
    case FeatureType::kBox:
      return f.center;
    case FeatureType::kWinding:
      return f.axis_point;
    case FeatureType::kPosition: {
      const Task& task = w.problem.tasks[i];
      if (task.target.rows() != 3 || task.target.cols() == 0) return std::nullopt;
      return Eigen::Vector3d(task.target.col(task.target.cols() - 1));
    }
    default:
      return std::nullopt;
  }
}

}  // namespace

std::vector<int> AttachedTasks(const Scenario& s, const ScenarioState& w,
                               const std::string& object) {
  const std::vector<std::string> names = ObjectNames(s);
  if (std::find(names.begin(), names.end(), object) == names.end()) {
    throw std::invalid_argument("unknown object '" + object + "' " + ObjectList(names));
  }
  std::vector<int> out;
  for (size_t i = 0; i < w.tasks.size() && i < w.problem.tasks.size(); ++i) {
    const std::optional<Eigen::Vector3d> p = TaskPoint(w, i);
    if (!p) continue;
    double best = std::numeric_limits<double>::infinity();
    std::string nearest;
    for (const std::string& name : names) {
      const PlacedObject& o = w.objects.objects[FindObject(w.objects, name)];
      const double d = (o.world_from_object.translation() - *p).norm();
      if (d < best) {
        best = d;
        nearest = name;
      }
    }
    if (nearest == object) out.push_back(static_cast<int>(i));
  }
  return out;
}

std::vector<int> ResolveAttachedTasks(const Scenario& s, const ScenarioState& w,
                                      const std::string& object, const ReplanOptions& options) {
  if (!options.attached_tasks) return AttachedTasks(s, w, object);
  std::vector<std::string> valid;
  for (const TaskSpec& t : s.spec.tasks) valid.push_back(t.name);
  std::vector<int> out;
  for (const std::string& name : *options.attached_tasks) {
    const auto it = std::find(valid.begin(), valid.end(), name);
    if (it == valid.end()) {
      throw std::invalid_argument("attached task '" + name + "' is not a task of the scenario " +
                                  ObjectList(valid, "tasks"));
    }
    out.push_back(static_cast<int>(it - valid.begin()));
  }
  return out;
}

void MoveObjectWithTargets(const Scenario& s, ScenarioState* w, const std::string& object,
                           const Eigen::Vector3d& position, const std::vector<int>& attached) {
  if (!position.allFinite()) {
    ObjectPosition(s, *w, object);  // throws, listing the valid names
    throw std::invalid_argument("MoveObject: non-finite position");
  }
  const Eigen::Vector3d delta = position - ObjectPosition(s, *w, object);
  for (int i : attached) {
    if (i < 0 || i >= static_cast<int>(w->tasks.size()) ||
        i >= static_cast<int>(w->problem.tasks.size())) {
      throw std::invalid_argument("MoveObjectWithTargets: task index " + std::to_string(i) +
                                  " out of range");
    }
  }
  for (int i : attached) {
    FeatureSpec& f = w->tasks[i].feature;
    if (f.type == FeatureType::kBox) f.center += delta;
    if (f.type == FeatureType::kWinding) f.axis_point += delta;
    Task& task = w->problem.tasks[i];
    if (f.type == FeatureType::kPosition && task.target.rows() == 3) {
      task.target.colwise() += delta;
    }
  }
  MoveObject(s, w, object, position);  // rebuilds the features from the moved task specs
}

ReplanWorkspace::ReplanWorkspace(const Scenario& s, const ScenarioState& w)
    : window(AttemptProblem(s, w, 0)), aico(window) {
  init.q.resize(window.q0.size(), window.num_steps + 1);
  init.dt = tau(window);
}

AicoResult Replan(const Scenario& s, const ScenarioState& state, int slice, const Eigen::VectorXd& q,
                  const Eigen::VectorXd& qdot, const Eigen::MatrixXd& previous, int shift,
                  const ReplanOptions& options, ReplanWorkspace* ws) {
  MotionProblem& w = ws->window;
  const int T = w.num_steps;
  const Eigen::Index n = w.q0.size();
  if (slice < 0 || shift < 0) throw std::invalid_argument("Replan: negative slice or shift");
  if (q.size() != n || qdot.size() != n || previous.rows() != n || previous.cols() != T + 1) {
    throw std::invalid_argument("Replan: q, q̇ must have " + std::to_string(n) +
                                " entries and the previous plan " + std::to_string(n) + "x" +
                                std::to_string(T + 1));
  }
  if (options.sweeps < 1) throw std::invalid_argument("Replan: sweeps must be >= 1");
  // The moved scene: new features, and their data (collision objects) in the workspace.
  RebuildTaskFeatures(s, state, &w);
  for (size_t i = 0; i < w.tasks.size(); ++i) {
    ws->aico.tasks.data[i] = w.tasks[i].feature->CreateData(s.robot);
  }
  ShiftTargets(state.problem, slice, &w);
  w.q0 = q;
  w.qdot0 = qdot;
  for (int j = 0; j <= T; ++j) {
    ws->init.q.col(j) = options.warm_start ? previous.col(std::min(shift + j, T)) : q;
  }
  AicoOptions o = AttemptOptions(s, 0);
  o.max_iterations = options.sweeps;
  if (options.damping >= 0.0) o.damping = options.damping;
  return SolveAico(w, o, &ws->aico, options.on_sweep, &ws->init);
}

RecedingPlan MakeRecedingPlan(const Trajectory& t, const Eigen::MatrixXd& velocities,
                              int start_slice) {
  RecedingPlan plan;
  plan.q = t.q;
  plan.start_slice = start_slice;
  if (velocities.size() > 0) {
    if (velocities.rows() != t.q.rows() || velocities.cols() != t.q.cols()) {
      throw std::invalid_argument("MakeRecedingPlan: velocities must match the trajectory's size");
    }
    plan.qdot = velocities;
    return plan;
  }
  plan.qdot = Eigen::MatrixXd::Zero(t.q.rows(), t.q.cols());
  for (Eigen::Index j = 0; j + 1 < t.q.cols(); ++j) {
    plan.qdot.col(j) = (t.q.col(j + 1) - t.q.col(j)) / t.dt;
  }
  return plan;
}

ReplanStep ReplanFrom(const Scenario& s, const ScenarioState& state, int elapsed,
                      const ReplanOptions& options, ReplanWorkspace* ws, RecedingPlan* plan,
                      AicoResult* result) {
  const int T = state.problem.num_steps;
  if (elapsed < 0 || elapsed > T || plan->q.cols() != T + 1 || plan->qdot.cols() != T + 1) {
    throw std::invalid_argument("ReplanFrom: elapsed must be in [0, " + std::to_string(T) +
                                "] and the plan have " + std::to_string(T + 1) + " columns");
  }
  ReplanStep step;
  step.slice = plan->start_slice + elapsed;
  step.time_s = step.slice * tau(state.problem);
  const double wall0 = WallMs(), cpu0 = ThreadCpuMs();
  AicoResult r = Replan(s, state, step.slice, plan->q.col(elapsed), plan->qdot.col(elapsed), plan->q,
                        elapsed, options, ws);
  step.wall_ms = WallMs() - wall0;
  step.cpu_ms = ThreadCpuMs() - cpu0;
  step.sweeps = r.iterations;
  step.status = r.status;
  step.cost = r.cost;
  step.collision_queries = r.collision_queries;
  *plan = MakeRecedingPlan(r.trajectory, r.velocities, step.slice);
  if (result != nullptr) *result = std::move(r);
  return step;
}

ReplanResult RunReplanning(const Scenario& s, const std::string& object, const ObjectPath& path,
                           const ReplanOptions& options) {
  if (path.t.empty()) throw std::invalid_argument("RunReplanning: empty object path");
  if (!(options.replan_period_s > 0.0) || !std::isfinite(options.replan_period_s)) {
    throw std::invalid_argument("RunReplanning: replan_period_s must be a finite number > 0");
  }
  if (options.sweeps < 1) throw std::invalid_argument("RunReplanning: sweeps must be >= 1");
  // The world of this run: a state of its own (the scenario itself never moves).
  const std::unique_ptr<ScenarioState> state = MakeScenarioState(s);
  ScenarioState* w = state.get();
  ObjectPosition(s, *w, object);  // throws for an unknown name, listing the valid ones
  const std::vector<int> attached = ResolveAttachedTasks(s, *w, object, options);
  ReplanResult out;
  out.object = FindObject(w->objects, object);
  const MotionProblem& base = w->problem;
  const int T = base.num_steps;
  const double tau_s = tau(base);
  const int n = static_cast<int>(base.q0.size());
  // At most T slices (no re-plan within the plan): a period of 1e300 s must not overflow lround.
  out.period_slices = std::max(1, static_cast<int>(std::lround(std::min(
                                      options.replan_period_s / tau_s, static_cast<double>(T)))));
  out.period_s = out.period_slices * tau_s;

  // g = 0: the full solve with the object at path(0).
  std::vector<Eigen::Vector3d> segment_position{ObjectPositionAt(path, 0.0)};
  std::vector<int> segment_start{0};
  MoveObjectWithTargets(s, w, object, segment_position.back(), attached);
  out.start_writhe_total = ReportWritheTotal(s, *w, base.q0);
  ReplanWorkspace ws(s, *w);
  {
    const double wall0 = WallMs(), cpu0 = ThreadCpuMs();
    out.initial = SolveAico(ws.window, AttemptOptions(s, 0), &ws.aico);
    out.initial_wall_ms = WallMs() - wall0;
    out.initial_cpu_ms = ThreadCpuMs() - cpu0;
  }
  // The current plan (its column 0 is executed at slice plan.start_slice).
  RecedingPlan plan = MakeRecedingPlan(out.initial.trajectory, out.initial.velocities, 0);
  out.executed.q.resize(n, T + 1);
  out.executed.dt = tau_s;

  for (int g = 0; g <= T; ++g) {
    out.executed.q.col(g) = plan.q.col(g - plan.start_slice);
    out.object_positions.push_back(segment_position.back());
    if (g == T || g % out.period_slices != 0 || g == 0) continue;
    // Re-plan at g (after executing it): the object moves, the window shifts.
    const Eigen::Vector3d position = ObjectPositionAt(path, g * tau_s);
    const double wall0 = WallMs(), cpu0 = ThreadCpuMs();
    MoveObjectWithTargets(s, w, object, position, attached);
    const double move_wall = WallMs() - wall0, move_cpu = ThreadCpuMs() - cpu0;
    ReplanStep step = ReplanFrom(s, *w, g - plan.start_slice, options, &ws, &plan);
    step.object_position = position;
    step.wall_ms += move_wall;  // move + window + AICO
    step.cpu_ms += move_cpu;
    out.replans.push_back(step);
    if (options.on_replan) options.on_replan(step);
    segment_start.push_back(g);
    segment_position.push_back(step.object_position);
  }
  segment_start.push_back(T);

  // Judge each segment with the object where it was during it; the last one fully, and when the
  // moving object is the report loop, with the through-the-loop criterion.
  SuccessCriteria criteria = s.success;
  criteria.through_loop = criteria.through_loop ||
                          (s.report_chain >= 0 && s.spec.writhe_report &&
                           s.spec.writhe_report->object.name == object &&
                           IsClosedLoop(w->report_object_chain));
  out.verdict = PlanVerdict{};
  double min_clearance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < segment_start.size(); ++i) {
    const int a = segment_start[i], b = segment_start[i + 1];
    MoveObjectWithTargets(s, w, object, segment_position[i], attached);
    Trajectory segment;
    segment.dt = tau_s;
    segment.q = out.executed.q.middleCols(a, b - a + 1);
    const bool last = i + 2 == segment_start.size();
    const PlanVerdict v = JudgePlan(s, *w, segment, last ? criteria : s.success);
    min_clearance = std::min(min_clearance, v.min_clearance_m);
    const bool along = v.reason == FailureReason::kJointLimits ||
                       v.reason == FailureReason::kCollision ||
                       v.reason == FailureReason::kTunnelled;
    if (last || along) {
      out.verdict = v;
      if (along && !last) {
        int offset = 0;  // resampled states of the earlier segments
        for (size_t k = 0; k < i; ++k) {
          Trajectory earlier;
          earlier.q = out.executed.q.middleCols(segment_start[k],
                                                segment_start[k + 1] - segment_start[k] + 1);
          offset += Densify(earlier, s.check_resolution).num_points() - 1;
        }
        out.verdict.step = v.step + offset;
        break;
      }
    }
  }
  out.verdict.min_clearance_m = min_clearance;
  out.verdict.collision_free = out.verdict.reason != FailureReason::kJointLimits &&
                               out.verdict.reason != FailureReason::kCollision;

  out.final_writhe_total = ReportWritheTotal(s, *w, out.executed.q.col(T));
  out.passed_through = out.verdict.passed_through;
  if (!out.verdict.loop_checked && s.report_chain >= 0 && IsClosedLoop(w->report_object_chain)) {
    // An earlier segment failed (the last was not judged): where the chain ends all the same.
    KinematicsData kin(s.robot);
    ForwardKinematics(s.robot, out.executed.q.col(T), &kin);
    Eigen::Matrix3Xd P;
    ChainPoints(s.robot, kin, s.report_chain, &P);
    out.passed_through = ChainThroughLoop(P, w->report_object_chain);
  }
  out.success = out.verdict.ok();

  std::vector<double> cpu, wall;
  double cpu_total = 0.0, wall_total = 0.0;
  for (const ReplanStep& r : out.replans) {
    cpu.push_back(r.cpu_ms);
    wall.push_back(r.wall_ms);
    cpu_total += r.cpu_ms;
    wall_total += r.wall_ms;
  }
  if (!cpu.empty()) {
    out.rate_hz = cpu_total > 0.0 ? 1000.0 * static_cast<double>(cpu.size()) / cpu_total : 0.0;
    out.wall_rate_hz =
        wall_total > 0.0 ? 1000.0 * static_cast<double>(wall.size()) / wall_total : 0.0;
    out.median_cpu_ms = Median(cpu);
    out.max_cpu_ms = *std::max_element(cpu.begin(), cpu.end());
    out.median_wall_ms = Median(wall);
    out.max_wall_ms = *std::max_element(wall.begin(), wall.end());
  }
  return out;
}

PlanReport ReplanReport(const ReplanResult& r) {
  PlanReport rep;
  rep.planner = PlannerName(Planner::kAico);
  rep.success = r.success;
  rep.status = r.replans.empty() ? r.initial.status : r.replans.back().status;
  rep.collision_checks = r.initial.collision_queries;
  rep.iterations = r.initial.iterations;
  rep.cost = r.replans.empty() ? r.initial.cost : r.replans.back().cost;
  double wall_ms = r.initial_wall_ms;
  for (const ReplanStep& step : r.replans) {
    rep.collision_checks += step.collision_queries;
    rep.iterations += step.sweeps;
    wall_ms += step.wall_ms;
  }
  rep.path_length = PathLength(r.executed);
  rep.time_s = wall_ms / 1000.0;
  rep.start_writhe_total = r.start_writhe_total;
  rep.final_writhe_total = r.final_writhe_total;
  rep.path_collision_free = r.verdict.collision_free;
  rep.cost_history = r.initial.cost_history;
  ApplyVerdict(r.verdict, &rep);
  rep.final_writhe_total = r.final_writhe_total;
  return rep;
}

}  // namespace planning
