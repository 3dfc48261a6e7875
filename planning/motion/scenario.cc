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
#include "planning/motion/internal/scenario_build.h"
#include "planning/motion/success.h"
#include "planning/motion/unwrap_geometry.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/pose.h"
#include "planning/robot/robot_io.h"
#include "planning/robot/srdf.h"
#include "topology/line_crossing.h"
#include "topology/winding.h"
#include "topology/writhe.h"
namespace planning {

using internal::BuildFeature;
using internal::BuildTask;
using internal::ObjectChain;

Eigen::VectorXd FeatureValue(const Robot& robot, const Feature& f, const Eigen::VectorXd& q) {
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  auto data = f.CreateData(robot);
  Eigen::VectorXd y(f.dim());
  f.Eval(robot, kin, data.get(), y, nullptr);
  return y;
}

double ReportWritheTotal(const Scenario& s, const Eigen::VectorXd& q, Eigen::MatrixXd* matrix) {
  return ReportWritheTotal(s, s.initial, q, matrix);
}

double ReportWritheTotal(const Scenario& s, const ScenarioState& w, const Eigen::VectorXd& q,
                         Eigen::MatrixXd* matrix, bool closed_by_chord) {
  if (s.report_chain < 0) {
    if (matrix != nullptr) matrix->resize(0, 0);
    return 0.0;
  }
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  Eigen::Matrix3Xd P;
  ChainPoints(s.robot, kin, s.report_chain, &P);
  if (closed_by_chord) {
    P.conservativeResize(3, P.cols() + 1);
    P.col(P.cols() - 1) = P.col(0);
  }
  const Eigen::MatrixXd W = topology::WritheMatrix(P, w.report_object_chain);
  if (matrix != nullptr) *matrix = W;
  return W.sum();
}

double ReportWinding(const Scenario& s, const Eigen::VectorXd& q) {
  return ReportWinding(s, s.initial, q);
}

double ReportWinding(const Scenario& s, const ScenarioState& w, const Eigen::VectorXd& q) {
  if (s.report_chain < 0) return 0.0;
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  Eigen::Matrix3Xd P;
  ChainPoints(s.robot, kin, s.report_chain, &P);
  return topology::WindingNumber(P, ReportAxis(s, w));
}

double ReportLineDistanceBeyondEnds(const Scenario& s, const Eigen::VectorXd& q) {
  const Eigen::Matrix3Xd& O = s.initial.report_object_chain;
  if (s.report_chain < 0 || O.cols() < 2 || O.col(0) == O.col(O.cols() - 1))
    return std::numeric_limits<double>::infinity();
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  Eigen::Matrix3Xd P;
  ChainPoints(s.robot, kin, s.report_chain, &P);
  return topology::LineDistanceBeyondEnds(P, O.col(0), O.col(O.cols() - 1));
}

topology::Axis ReportAxis(const Scenario& s) { return ReportAxis(s, s.initial); }

topology::Axis ReportAxis(const Scenario& s, const ScenarioState& w) {
  const Eigen::Matrix3Xd& O = w.report_object_chain;
  if (s.report_chain < 0 || O.cols() < 2) throw std::invalid_argument("ReportAxis: no report pair");
  topology::Axis axis;
  axis.point = O.col(0);
  axis.direction = O.col(O.cols() - 1) - O.col(0);
  return axis;
}

MotionProblem AttemptProblem(const Scenario& s, int k) { return AttemptProblem(s, s.initial, k); }

MotionProblem AttemptProblem(const Scenario& s, const ScenarioState& w, int k) {
  if (k < 0 || k >= static_cast<int>(s.aico_attempts.size())) {
    throw std::invalid_argument("AttemptProblem: no AICO attempt " + std::to_string(k));
  }
  const ProblemSpec& ps = s.spec.problem;
  MotionProblem p;
  p.robot = &s.robot;
  p.q0 = s.initial.problem.q0;  // the resolved start
  p.num_steps = ps.num_steps;
  p.duration = ps.duration;
  p.dynamic = ps.dynamic;
  p.h_rate = ps.h_rate;
  p.w_rate = ps.w_rate;
  p.q_rate = ps.q_rate;
  const Eigen::VectorXd& scale = s.aico_attempts[k].precision_scale;
  for (size_t i = 0; i < w.tasks.size(); ++i) {
    p.tasks.push_back(BuildTask(s, w, w.tasks[i], p.q0, &s.goal_q));
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

std::vector<std::string> ObjectNames(const Scenario& s) {
  std::vector<std::string> names;
  for (const ObjectSpec& o : s.spec.objects) names.push_back(o.name);
  return names;
}

void RebuildTaskFeatures(const Scenario& s, const ScenarioState& w, MotionProblem* problem) {
  if (problem->tasks.size() != w.tasks.size()) {
    throw std::invalid_argument("RebuildTaskFeatures: the problem has " +
                                std::to_string(problem->tasks.size()) + " tasks, the scenario " +
                                std::to_string(w.tasks.size()));
  }
  for (size_t i = 0; i < problem->tasks.size(); ++i) {
    problem->tasks[i].feature = BuildFeature(s, w, w.tasks[i].feature);
  }
}

std::unique_ptr<ScenarioState> MakeScenarioState(const Scenario& s) {
  auto w = std::make_unique<ScenarioState>();
  w->objects = s.initial.objects;
  w->env = s.initial.env;
  w->report_object_chain = s.initial.report_object_chain;
  w->tasks = s.initial.tasks;
  // Built as SetUpScenario built the initial problem, with features of this state's objects.
  w->problem = AttemptProblem(s, *w, 0);
  return w;
}

namespace {

// Index of object `name` in the spec, or throws "unknown object 'X' (objects: a, b)".
size_t SpecObjectIndex(const Scenario& s, const std::string& name) {
  for (size_t i = 0; i < s.spec.objects.size(); ++i) {
    if (s.spec.objects[i].name == name) return i;
  }
  std::string list;
  for (const std::string& n : ObjectNames(s)) list += (list.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown object '" + name +
                              "' (objects: " + (list.empty() ? "none" : list) + ")");
}

}  // namespace

Eigen::Vector3d ObjectPosition(const Scenario& s, const ScenarioState& w, const std::string& name) {
  SpecObjectIndex(s, name);
  return w.objects.objects[FindObject(w.objects, name)].world_from_object.translation();
}

void MoveObject(const Scenario& s, ScenarioState* w, const std::string& name,
                const Eigen::Vector3d& position) {
  SpecObjectIndex(s, name);
  if (!position.allFinite()) throw std::invalid_argument("MoveObject: non-finite position");
  PlacedObject& placed = w->objects.objects[FindObject(w->objects, name)];
  const Eigen::Vector3d delta = position - placed.world_from_object.translation();
  placed.world_from_object.translation() = position;
  for (PlacedObject& e : w->env.objects) {
    if (e.name == name || e.name.rfind(name + "#", 0) == 0) e.world_from_object.pretranslate(delta);
  }
  if (s.spec.writhe_report && s.spec.writhe_report->object.name == name) {
    w->report_object_chain =
        ObjectChain(*w, s.spec.writhe_report->object, s.spec.writhe_report->object_chain);
  }
  RebuildTaskFeatures(s, *w, &w->problem);
}

std::unique_ptr<Scenario> LoadScenario(const std::string& path,
                                       const ScenarioOverrides& overrides) {
  ScenarioSpec spec = ParseScenarioSpec(path, overrides.search_roots);
  // The geometry first: it may replace the robot (and clear the file's SRDF), which the
  // command-line package paths and SRDF below then apply to.
  if (!overrides.geometry.empty()) {
    ApplyUnwrapGeometry(ReadUnwrapGeometry(overrides.geometry, overrides.search_roots), &spec);
  }
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
