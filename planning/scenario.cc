#include "planning/scenario.h"

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "planning/internal/ompl_planners.h"
#include "planning/robot_io.h"
#include "topology/writhe.h"

namespace planning {
namespace {

using nlohmann::json;

// A JSON value with the file and the JSON path it came from, for error messages.
struct Node {
  const json& j;  // NOLINT: a view into the parsed document
  std::string file;
  std::string path;

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument(file + ": " + (path.empty() ? "(root)" : path) + ": " + what);
  }
  bool Has(const std::string& key) const { return j.is_object() && j.contains(key); }
  Node At(const std::string& key) const {
    if (!j.is_object()) Fail("expected an object");
    if (!j.contains(key)) Fail("missing key '" + key + "'");
    return {j.at(key), file, path.empty() ? key : path + "." + key};
  }
  Node At(size_t i) const { return {j.at(i), file, path + "[" + std::to_string(i) + "]"}; }
  size_t Size() const {
    if (!j.is_array()) Fail("expected an array");
    return j.size();
  }
  double Number() const {
    if (!j.is_number()) Fail("expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) Fail("not a finite number");
    return v;
  }
  double Number(const std::string& key, double fallback) const {
    return Has(key) ? At(key).Number() : fallback;
  }
  int Int(const std::string& key, int fallback) const {
    if (!Has(key)) return fallback;
    const Node n = At(key);
    if (!n.j.is_number_integer()) n.Fail("expected an integer");
    return n.j.get<int>();
  }
  bool Bool(const std::string& key, bool fallback) const {
    if (!Has(key)) return fallback;
    const Node n = At(key);
    if (!n.j.is_boolean()) n.Fail("expected true or false");
    return n.j.get<bool>();
  }
  std::string String() const {
    if (!j.is_string()) Fail("expected a string");
    return j.get<std::string>();
  }
  std::string String(const std::string& key, const std::string& fallback) const {
    return Has(key) ? At(key).String() : fallback;
  }
  Eigen::VectorXd Vector(int expected = -1) const {
    const size_t n = Size();
    if (expected >= 0 && static_cast<int>(n) != expected) {
      Fail("expected " + std::to_string(expected) + " numbers, got " + std::to_string(n));
    }
    Eigen::VectorXd v(static_cast<Eigen::Index>(n));
    for (size_t i = 0; i < n; ++i) v[static_cast<Eigen::Index>(i)] = At(i).Number();
    return v;
  }
  Eigen::Vector3d Vec3(const std::string& key, const Eigen::Vector3d& fallback) const {
    return Has(key) ? Eigen::Vector3d(At(key).Vector(3)) : fallback;
  }
};

// Calls f and prefixes any std::invalid_argument with the node's location.
template <typename F>
auto Located(const Node& n, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    n.Fail(e.what());
  }
}

std::string Resolve(const std::string& base_dir, const std::string& rel) {
  const std::filesystem::path p(rel);
  return p.is_absolute() ? rel : (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

Eigen::Isometry3d Pose(const Node& n) {
  const Eigen::Vector3d xyz = n.Vec3("xyz", Eigen::Vector3d::Zero());
  const Eigen::Vector3d rpy = n.Vec3("rpy", Eigen::Vector3d::Zero());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = xyz;
  pose.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return pose;
}

Eigen::Matrix3Xd ObjectChain(const Scenario& s, const Node& n, const std::string& obj_key,
                             const std::string& chain_key) {
  const Node on = n.At(obj_key);
  const int object = Located(on, [&] { return FindObject(s.objects, on.String()); });
  const Node cn = n.At(chain_key);
  const int chain =
      Located(cn, [&] { return FindChain(s.objects.objects[object].model, cn.String()); });
  return ObjectChainPoints(s.objects, object, chain);
}

std::unique_ptr<Feature> BuildFeature(const Scenario& s, const Node& n) {
  const std::string type = n.At("type").String();
  const Robot& r = s.robot;
  auto link = [&](const std::string& key) {
    const Node ln = n.At(key);
    return Located(ln, [&] { return FindLink(r, ln.String()); });
  };
  auto chain = [&](const std::string& key) {
    const Node cn = n.At(key);
    return Located(cn, [&] { return FindChain(r, cn.String()); });
  };
  return Located(n, [&]() -> std::unique_ptr<Feature> {
    if (type == "position") {
      return MakePositionFeature(r, link("link"), n.Vec3("offset", Eigen::Vector3d::Zero()));
    }
    if (type == "axis_alignment") {
      return MakeAxisAlignmentFeature(r, link("link"), n.Vec3("axis", Eigen::Vector3d::UnitZ()),
                                      Eigen::Vector3d(n.At("direction").Vector(3)));
    }
    if (type == "joint_limits") return MakeJointLimitFeature(r, n.Number("margin", 0.0));
    if (type == "joint_position") return MakeJointPositionFeature(r);
    if (type == "box") {
      return MakeBoxFeature(r, link("link"), n.Vec3("offset", Eigen::Vector3d::Zero()),
                            Eigen::Vector3d(n.At("center").Vector(3)),
                            Eigen::Vector3d(n.At("half_extent").Vector(3)),
                            n.Number("margin", 0.0));
    }
    if (type == "writhe") {
      const std::string out = n.String("output", "matrix");
      if (out != "matrix" && out != "total")
        n.At("output").Fail("expected \"matrix\" or \"total\"");
      return MakeWritheFeature(r, chain("chain"), ObjectChain(s, n, "object", "object_chain"),
                               out == "total" ? WritheOutput::kTotal : WritheOutput::kMatrix);
    }
    if (type == "winding") {
      topology::Axis axis;
      axis.point = Eigen::Vector3d(n.At("axis_point").Vector(3));
      axis.direction = Eigen::Vector3d(n.At("axis_direction").Vector(3));
      return MakeWindingFeature(r, chain("chain"), axis);
    }
    if (type == "collision") {
      return MakeCollisionFeature(r, s.env, s.collision, n.Number("margin", 0.05));
    }
    n.At("type").Fail("unknown feature type '" + type +
                      "' (position, axis_alignment, joint_limits, joint_position, box, writhe, "
                      "winding, collision)");
  });
}

// Feature value at q.
Eigen::VectorXd FeatureAt(const Robot& robot, const Feature& f, const Eigen::VectorXd& q) {
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  auto data = f.CreateData(robot);
  Eigen::VectorXd y(f.dim());
  f.Eval(robot, kin, data.get(), y, nullptr);
  return y;
}

// Task from its JSON node; target resolution needs q0 (and q̂_T for "final_pose").
Task BuildTask(const Scenario& s, const Node& n, int T, const Eigen::VectorXd& q0,
               const Eigen::VectorXd* q_final) {
  Task task;
  task.name = n.String("name", "task");
  task.feature = BuildFeature(s, n.At("feature"));
  task.order = n.Int("order", 0);
  if (task.order != 0 && task.order != 1) n.At("order").Fail("expected 0 or 1");
  const double mid = n.Number("precision", 0.0);
  const double fin = n.Number("final_precision", mid);
  if (mid < 0 || fin < 0) n.Fail("precisions must be >= 0");
  const int dim = task.feature->dim();
  static const json kNoTarget = json::object();
  const Node tn = n.Has("target") ? n.At("target") : Node{kNoTarget, n.file, n.path + ".target"};
  const std::string type = n.Has("target") ? tn.String("type", "value") : "zero";
  auto value = [&]() {
    const Node vn = tn.At("value");
    if (vn.j.is_number() && dim == 1) return Eigen::VectorXd::Constant(1, vn.Number()).eval();
    if (vn.j.is_number()) return Eigen::VectorXd::Constant(dim, vn.Number()).eval();
    return vn.Vector(dim);
  };
  if (type == "zero" || type == "value") {
    SetConstantTarget(&task, type == "zero" ? Eigen::VectorXd::Zero(dim).eval() : value(), mid, T);
    task.precision[T] = fin;
  } else if (type == "interpolate") {
    SetInterpolatedTarget(&task, FeatureAt(s.robot, *task.feature, q0), value(), mid, fin, T);
  } else if (type == "final_pose") {
    if (q_final == nullptr)
      tn.Fail("\"final_pose\" targets cannot be used by the final-pose tasks");
    SetInterpolatedTarget(&task, FeatureAt(s.robot, *task.feature, q0),
                          FeatureAt(s.robot, *task.feature, *q_final), mid, fin, T);
  } else {
    tn.At("type").Fail("unknown target type '" + type + "' (zero, value, interpolate, final_pose)");
  }
  return task;
}

// Writhe continuation (see scenario.h): from q toward total writhe `target` in steps.
Eigen::VectorXd WritheContinuation(const Scenario& s, const Eigen::VectorXd& from, double target,
                                   double step, double margin) {
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
  }
  return q;
}

SweepMode ParseSweep(const Node& n) {
  const std::string m = n.String();
  if (m == "forwardly") return SweepMode::kForwardly;
  if (m == "symmetric") return SweepMode::kSymmetric;
  if (m == "local_gauss_newton") return SweepMode::kLocalGaussNewton;
  n.Fail("unknown sweep mode '" + m + "' (forwardly, symmetric, local_gauss_newton)");
}

int TaskIndex(const Scenario& s, const Node& n) {
  const std::string name = n.String();
  for (size_t i = 0; i < s.problem.tasks.size(); ++i) {
    if (s.problem.tasks[i].name == name) return static_cast<int>(i);
  }
  n.Fail("no task named '" + name + "'");
}

}  // namespace

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

std::unique_ptr<Scenario> LoadScenario(const std::string& path,
                                       const ScenarioOverrides& overrides) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open scenario file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(path + ": JSON parse error: " + e.what());
  }
  const Node root{doc, path, ""};
  const std::string dir = std::filesystem::path(path).parent_path().string();
  auto s = std::make_unique<Scenario>();
  s->source = path;
  s->name = root.String("name", std::filesystem::path(path).stem().string());

  // Robot and objects.
  {
    const Node rn = root.At("robot");
    s->robot = Located(rn, [&] { return LoadRobot(Resolve(dir, rn.String())); });
  }
  if (root.Has("objects")) {
    const Node objs = root.At("objects");
    for (size_t i = 0; i < objs.Size(); ++i) {
      const Node on = objs.At(i);
      const std::string name = on.At("name").String();
      const Node un = on.At("urdf");
      Robot model = Located(un, [&] { return LoadRobot(Resolve(dir, un.String())); });
      const Eigen::Isometry3d pose = Pose(on);
      Located(on, [&] { AddObject(model, pose, name, &s->objects); });
      if (!on.Bool("collide", true)) continue;
      if (on.Has("capsules")) {
        const Node cn = on.At("capsules");
        const int obj = static_cast<int>(s->objects.objects.size()) - 1;
        const Node chn = cn.At("chain");
        const int chain = Located(chn, [&] { return FindChain(model, chn.String()); });
        const Eigen::Matrix3Xd pts = ObjectChainPoints(s->objects, obj, chain);
        const double radius = cn.At("radius").Number();
        for (Eigen::Index k = 0; k + 1 < pts.cols(); ++k) {
          const Eigen::Vector3d a = pts.col(k), b = pts.col(k + 1);
          Geometry g;
          g.kind = Geometry::Kind::kCapsule;
          g.size = Eigen::Vector3d(radius, (b - a).norm(), 0.0);
          Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
          T.translation() = 0.5 * (a + b);
          T.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), b - a)
                           .toRotationMatrix();
          const std::string part = name + "#" + std::to_string(k);
          AddObject(MakePrimitiveObject(part, g), T, part, &s->env);
        }
      } else {
        AddObject(model, pose, name, &s->env);
      }
    }
  }
  if (root.Has("robot_chains")) {
    // Extra chains on the robot: {"name", "closed", "points": [{"link", "xyz"}, ...]}.
    const Node rc = root.At("robot_chains");
    for (size_t i = 0; i < rc.Size(); ++i) {
      const Node cn = rc.At(i);
      ChainSpec spec;
      spec.name = cn.At("name").String();
      spec.closed = cn.Bool("closed", false);
      const Node pts = cn.At("points");
      if (pts.Size() < 2) pts.Fail("a chain needs at least 2 points");
      spec.point_local.resize(3, static_cast<Eigen::Index>(pts.Size()));
      for (size_t k = 0; k < pts.Size(); ++k) {
        const Node pn = pts.At(k);
        const Node ln = pn.At("link");
        spec.point_link.push_back(Located(ln, [&] { return FindLink(s->robot, ln.String()); }));
        spec.point_local.col(static_cast<Eigen::Index>(k)) =
            pn.Vec3("xyz", Eigen::Vector3d::Zero());
      }
      s->robot.chains.push_back(spec);
    }
  }
  if (root.Has("collision")) {
    const Node cn = root.At("collision");
    s->collision.self_collision = cn.Bool("self", true);
    if (cn.Has("disabled_pairs")) {
      const Node dp = cn.At("disabled_pairs");
      for (size_t i = 0; i < dp.Size(); ++i) {
        const Node pn = dp.At(i);
        if (pn.Size() != 2) pn.Fail("expected [link_a, link_b]");
        s->collision.disabled_pairs.emplace_back(pn.At(0).String(), pn.At(1).String());
      }
    }
    if (cn.Has("disabled_groups")) {
      // Every pair of links whose names start with prefixes of the same group is not checked.
      const Node gs = cn.At("disabled_groups");
      for (size_t g = 0; g < gs.Size(); ++g) {
        const Node gn = gs.At(g);
        std::vector<std::string> prefixes;
        for (size_t i = 0; i < gn.Size(); ++i) prefixes.push_back(gn.At(i).String());
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
    }
  }
  // Validate collision options once (unknown link names throw here, with the JSON path).
  if (root.Has("collision")) {
    Located(root.At("collision"), [&] { CollisionData check(s->robot, s->env, s->collision); });
  }
  if (root.Has("writhe_report")) {
    const Node wn = root.At("writhe_report");
    const Node cn = wn.At("chain");
    s->report_chain = Located(cn, [&] { return FindChain(s->robot, cn.String()); });
    s->report_object_chain = ObjectChain(*s, wn, "object", "object_chain");
  }

  // Problem parameters.
  const int n = num_dofs(s->robot);
  MotionProblem& p = s->problem;
  p.robot = &s->robot;
  if (root.Has("problem")) {
    const Node pn = root.At("problem");
    p.num_steps = pn.Int("T", p.num_steps);
    p.duration = pn.Number("duration", p.duration);
    p.dynamic = pn.Bool("dynamic", p.dynamic);
    p.h_rate = pn.Number("h_rate", p.h_rate);
    p.w_rate = pn.Number("w_rate", p.w_rate);
    p.q_rate = pn.Number("q_rate", p.q_rate);
    if (p.num_steps < 1 || p.num_steps > 10000) pn.At("T").Fail("T must be in 1..10000");
  }
  const int T = p.num_steps;

  // Start configuration.
  Eigen::VectorXd unwrapped;
  {
    const Node sn = root.At("start");
    if (sn.Has("q")) {
      const Node qn = sn.At("q");
      p.q0 = qn.j.is_string() && qn.String() == "zero" ? Eigen::VectorXd::Zero(n) : qn.Vector(n);
    } else if (sn.Has("coil")) {
      const Node cn = sn.At("coil");
      if (s->report_chain < 0) cn.Fail("a coil start needs \"writhe_report\"");
      double wrap =
          overrides.start_wrap_deg ? *overrides.start_wrap_deg : cn.Number("wrap_deg", 720.0);
      if (!(wrap >= 0.0 && wrap <= 2000.0)) cn.Fail("wrap_deg must be in [0, 2000]");
      const double step = cn.Number("step", 0.05);
      const double margin = cn.Number("margin", 0.05);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
      const double w0 = ReportWritheTotal(*s, zero);
      const double sign = w0 < 0 ? -1.0 : 1.0;
      p.q0 = WritheContinuation(*s, zero, sign * wrap / 360.0, step, margin);
      unwrapped = WritheContinuation(*s, zero, 0.0, step, margin);
    } else {
      sn.Fail("expected \"q\" or \"coil\"");
    }
  }
  s->start_wrap_deg = 360.0 * std::abs(ReportWritheTotal(*s, p.q0));

  // Final-pose estimate over the listed tasks (their targets at T).
  const Node tasks_node = root.At("tasks");
  std::vector<std::string> fp_tasks;
  FinalPoseOptions fpo;
  std::string fp_init = "start";
  Eigen::VectorXd fp_init_q;
  if (root.Has("final_pose")) {
    const Node fn = root.At("final_pose");
    const Node ln = fn.At("tasks");
    for (size_t i = 0; i < ln.Size(); ++i) fp_tasks.push_back(ln.At(i).String());
    fpo.alpha = fn.Number("alpha", fpo.alpha);
    fpo.prior_scale = fn.Number("prior_scale", fpo.prior_scale);
    if (fn.Has("init") && fn.At("init").j.is_array()) {
      fp_init = "q";
      fp_init_q = fn.At("init").Vector(n);
    } else {
      fp_init = fn.String("init", fp_init);
    }
    if (fp_init != "start" && fp_init != "unwrapped" && fp_init != "q") {
      fn.At("init").Fail("expected \"start\", \"unwrapped\" or a configuration");
    }
    if (fp_init == "unwrapped" && unwrapped.size() == 0) {
      fn.At("init").Fail("\"unwrapped\" needs a coil start");
    }
  }
  s->goal_q = p.q0;
  if (!fp_tasks.empty()) {
    MotionProblem fp;
    fp.robot = &s->robot;
    fp.q0 = p.q0;
    fp.num_steps = T;
    fp.duration = p.duration;
    fp.dynamic = false;  // the kinematic prior N(q0, T W⁻¹)
    fp.w_rate = p.w_rate;
    for (const std::string& name : fp_tasks) {
      bool found = false;
      for (size_t i = 0; i < tasks_node.Size(); ++i) {
        const Node tn = tasks_node.At(i);
        if (tn.String("name", "") != name) continue;
        fp.tasks.push_back(BuildTask(*s, tn, T, p.q0, nullptr));
        found = true;
      }
      if (!found) root.At("final_pose").At("tasks").Fail("no task named '" + name + "'");
    }
    TaskWorkspace ws(fp);
    const Eigen::VectorXd init =
        fp_init == "unwrapped" ? unwrapped : (fp_init == "q" ? fp_init_q : p.q0);
    s->goal_q = EstimateFinalPose(fp, fpo, &ws, &init).q;
  }

  // The tasks.
  for (size_t i = 0; i < tasks_node.Size(); ++i) {
    p.tasks.push_back(BuildTask(*s, tasks_node.At(i), T, p.q0, &s->goal_q));
  }
  Located(root, [&] { ValidateProblem(p); });

  // Solver options.
  if (root.Has("aico")) {
    const Node an = root.At("aico");
    AicoOptions& a = s->aico;
    a.max_iterations = an.Int("max_iterations", a.max_iterations);
    a.tolerance = an.Number("tolerance", a.tolerance);
    a.damping = an.Number("damping", a.damping);
    if (an.Has("sweep_mode")) a.sweep_mode = ParseSweep(an.At("sweep_mode"));
    a.max_step = an.Number("max_step", a.max_step);
    a.rollout_init = an.Bool("rollout_init", a.rollout_init);
    a.rollout_prior = an.Number("rollout_prior", a.rollout_prior);
    a.rollout_iterations = an.Int("rollout_iterations", a.rollout_iterations);
  }
  if (root.Has("aico") && root.At("aico").Has("retry")) {
    // A second AICO attempt when the first fails: per-task precision multipliers (by task name)
    // and its own iteration limit. Its checks add to the same report.
    const Node rn = root.At("aico").At("retry");
    s->has_retry = true;
    s->retry_aico = s->aico;
    s->retry_aico.max_iterations = rn.Int("max_iterations", s->aico.max_iterations);
    MotionProblem& rp = s->retry_problem;
    rp.robot = &s->robot;
    rp.q0 = p.q0;
    rp.qdot0 = p.qdot0;
    rp.num_steps = p.num_steps;
    rp.duration = p.duration;
    rp.dynamic = p.dynamic;
    rp.h_rate = p.h_rate;
    rp.w_rate = p.w_rate;
    rp.q_rate = p.q_rate;
    for (size_t i = 0; i < tasks_node.Size(); ++i) {
      rp.tasks.push_back(BuildTask(*s, tasks_node.At(i), T, p.q0, &s->goal_q));
    }
    if (rn.Has("precision_scale")) {
      const Node sc = rn.At("precision_scale");
      if (!sc.j.is_object()) sc.Fail("expected {\"task name\": factor, ...}");
      for (const auto& item : sc.j.items()) {
        const Node fn{item.value(), sc.file, sc.path + "." + item.key()};
        const int idx = TaskIndex(*s, Node{json(item.key()), sc.file, fn.path});
        const double f = fn.Number();
        if (!(f > 0.0)) fn.Fail("expected a positive factor");
        rp.tasks[idx].precision *= f;
      }
    }
    Located(root.At("aico").At("retry"), [&] { ValidateProblem(rp); });
  }
  if (root.Has("rrt")) {
    const Node rn = root.At("rrt");
    RrtOptions& r = s->rrt;
    r.range = rn.Number("range", r.range);
    r.resolution = rn.Number("resolution", r.resolution);
    r.goal_bias = rn.Number("goal_bias", r.goal_bias);
    r.max_checks = rn.Int("max_checks", static_cast<int>(r.max_checks));
  }
  s->check_resolution =
      root.Number("check_resolution", s->rrt.resolution > 0 ? s->rrt.resolution : 0.02);
  if (root.Has("success")) {
    const Node sn = root.At("success");
    s->success.writhe_total_below = sn.Number("writhe_total_below", -1.0);
    if (sn.Has("position")) {
      const Node pn = sn.At("position");
      s->success.position_task = TaskIndex(*s, pn.At("task"));
      s->success.position_tolerance = pn.Number("tolerance", 0.05);
    }
    if (sn.Has("inside_box")) s->success.box_task = TaskIndex(*s, sn.At("inside_box"));
  }
  return s;
}

Planner ParsePlanner(const std::string& name) {
  if (name == "aico") return Planner::kAico;
  if (name == "rrt") return Planner::kRrt;
  if (name == "birrt") return Planner::kBiRrt;
  if (name == "ompl-rrt" || name == "ompl-rrtconnect") {
    if (!OmplAvailable()) {
      throw std::invalid_argument("planner '" + name +
                                  "': topoplan was built without OMPL (apt-get install "
                                  "libompl-dev, then re-run cmake)");
    }
    return name == "ompl-rrt" ? Planner::kOmplRrt : Planner::kOmplRrtConnect;
  }
  throw std::invalid_argument("unknown planner '" + name +
                              "' (aico, rrt, birrt, ompl-rrt, ompl-rrtconnect)");
}

bool OmplAvailable() {
#ifdef TOPOPLAN_HAVE_OMPL
  return true;
#else
  return false;
#endif
}

const char* PlannerName(Planner planner) {
  switch (planner) {
    case Planner::kAico:
      return "aico";
    case Planner::kRrt:
      return "rrt";
    case Planner::kBiRrt:
      return "birrt";
    case Planner::kOmplRrt:
      return "ompl-rrt";
    case Planner::kOmplRrtConnect:
      return "ompl-rrtconnect";
  }
  return "?";
}

namespace {

// Success criteria at the final configuration.
bool MeetsCriteria(const Scenario& s, const Eigen::VectorXd& q, double final_writhe) {
  const SuccessCriteria& c = s.success;
  if (c.writhe_total_below >= 0.0 && !(std::abs(final_writhe) < c.writhe_total_below)) {
    return false;
  }
  const int T = s.problem.num_steps;
  for (int idx : {c.position_task, c.box_task}) {
    if (idx < 0) continue;
    const Task& task = s.problem.tasks[idx];
    const Eigen::VectorXd y = FeatureAt(s.robot, *task.feature, q);
    const double err = (y - task.target.col(T)).norm();
    if (idx == c.position_task && err > c.position_tolerance) return false;
    if (idx == c.box_task && err > 1e-9) return false;
  }
  return true;
}

}  // namespace

PlanResult RunPlanner(const Scenario& s, Planner planner, unsigned seed,
                      const AicoCallback& callback) {
  PlanResult out;
  PlanReport& rep = out.report;
  rep.planner = PlannerName(planner);
  const int n = num_dofs(s.robot);
  CollisionData coll(s.robot, s.env, s.collision);
  KinematicsData kin(s.robot);
  const Eigen::VectorXd lo = LowerLimits(s.robot), hi = UpperLimits(s.robot);
  // The validity checker shared by the RRTs and the validation of every output path.
  const ValidityFn valid = [&](const Eigen::VectorXd& q) {
    for (int k = 0; k < n; ++k) {
      if (q[k] < lo[k] || q[k] > hi[k]) return false;
    }
    ForwardKinematics(s.robot, q, &kin);
    return !InCollision(s.robot, kin, &coll);
  };
  const auto t0 = std::chrono::steady_clock::now();
  bool found = false;
  if (planner == Planner::kAico) {
    // One attempt: solve, then validate the path at the edge resolution (counted: a plan is only
    // usable once checked) and test the success criteria.
    auto attempt = [&](const MotionProblem& problem, const AicoOptions& options) {
      AicoWorkspace ws(problem);
      const AicoResult r = SolveAico(problem, options, &ws, callback);
      rep.status = r.status;
      rep.iterations += r.iterations;
      rep.cost = r.cost;
      rep.cost_history = r.cost_history;
      rep.collision_checks += r.collision_queries;
      rep.narrow_phase_calls += NarrowPhaseCalls(problem, ws.tasks);
      out.trajectory = r.trajectory;
      const std::int64_t q0 = coll.queries, n0 = coll.narrow_phase_calls;
      rep.path_collision_free = r.status != SolveStatus::kInvalidInput &&
                                PathIsValid(out.trajectory, s.check_resolution, valid);
      rep.collision_checks += coll.queries - q0;
      rep.narrow_phase_calls += coll.narrow_phase_calls - n0;
      const Eigen::VectorXd q_end = out.trajectory.q.col(out.trajectory.num_points() - 1);
      return rep.path_collision_free && MeetsCriteria(s, q_end, ReportWritheTotal(s, q_end));
    };
    found = attempt(s.problem, s.aico);
    if (!found && s.has_retry) {
      ++rep.attempts;
      found = attempt(s.retry_problem, s.retry_aico);
    }
    found = found || out.trajectory.num_points() > 0;
  } else {
    RrtProblem rp;
    rp.lower = lo;
    rp.upper = hi;
    for (int k = 0; k < n; ++k) {  // continuous joints: one turn around the start
      if (!std::isfinite(rp.lower[k])) rp.lower[k] = s.problem.q0[k] - M_PI;
      if (!std::isfinite(rp.upper[k])) rp.upper[k] = s.problem.q0[k] + M_PI;
    }
    rp.start = s.problem.q0;
    rp.goal = s.goal_q;
    std::mt19937 rng(seed);
    RrtResult r;
    switch (planner) {
      case Planner::kRrt:
        r = PlanRrt(rp, s.rrt, valid, &rng);
        break;
      case Planner::kBiRrt:
        r = PlanBiRrt(rp, s.rrt, valid, &rng);
        break;
      case Planner::kOmplRrt:
      case Planner::kOmplRrtConnect:
#ifdef TOPOPLAN_HAVE_OMPL
        r = internal::PlanOmpl(planner == Planner::kOmplRrt ? internal::OmplPlanner::kRrt
                                                            : internal::OmplPlanner::kRrtConnect,
                               rp, s.rrt, valid, seed);
        break;
#else
        throw std::invalid_argument(std::string("planner '") + PlannerName(planner) +
                                    "': topoplan was built without OMPL");
#endif
      case Planner::kAico:
        break;
    }
    rep.status = r.status;
    rep.iterations = r.iterations;
    rep.collision_checks = coll.queries;
    rep.narrow_phase_calls = coll.narrow_phase_calls;
    out.trajectory = r.path;
    found = r.status == SolveStatus::kConverged;
  }
  // RRT paths are checked edge by edge while planning; re-check at the scenario's resolution.
  if (planner != Planner::kAico && found && out.trajectory.num_points() > 0) {
    CollisionData recheck(s.robot, s.env, s.collision);
    const ValidityFn free = [&](const Eigen::VectorXd& q) {
      for (int k = 0; k < n; ++k) {
        if (q[k] < lo[k] || q[k] > hi[k]) return false;
      }
      ForwardKinematics(s.robot, q, &kin);
      return !InCollision(s.robot, kin, &recheck);
    };
    rep.path_collision_free = PathIsValid(out.trajectory, s.check_resolution, free);
  }
  rep.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Report quantities (not counted).
  rep.start_writhe_total = ReportWritheTotal(s, s.problem.q0);
  if (out.trajectory.num_points() > 0) {
    const Eigen::VectorXd q_end = out.trajectory.q.col(out.trajectory.num_points() - 1);
    rep.final_writhe_total = ReportWritheTotal(s, q_end);
    rep.path_length = PathLength(out.trajectory);
    if (planner != Planner::kAico) rep.cost = rep.path_length;
    // Minimum clearance along the densified path (pairs within 0.2 m; 0.2 if none is closer).
    CollisionData metric(s.robot, s.env, s.collision);
    std::vector<ProximityPair> pairs;
    double clearance = 0.2;
    const Trajectory dense = Densify(out.trajectory, s.check_resolution);
    for (int t = 0; t < dense.num_points(); ++t) {
      ForwardKinematics(s.robot, dense.q.col(t), &kin);
      ComputeProximity(s.robot, kin, 0.2, &metric, &pairs);
      for (const ProximityPair& p : pairs) clearance = std::min(clearance, p.distance);
    }
    rep.min_clearance_m = clearance;
    rep.success =
        found && rep.path_collision_free && MeetsCriteria(s, q_end, rep.final_writhe_total);
  } else {
    rep.final_writhe_total = rep.start_writhe_total;
    rep.success = false;
  }
  return out;
}

}  // namespace planning
