#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/assets.h"
#include "base/numbers.h"
#include "base/str_cat.h"
#include "planning/features/position_feature.h"
#include "planning/motion/internal/scenario_build.h"
#include "planning/motion/internal/start_coil.h"
#include "planning/motion/robot_scene.h"
#include "planning/motion/scenario.h"
#include "planning/motion/success.h"
#include "planning/robot/ik.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/pose.h"
#include "planning/robot/robot_io.h"
#include "planning/robot/srdf.h"
#include "topology/winding.h"
#include "topology/writhe.h"
namespace planning {

using internal::BuildTask;
using internal::FindIn;
using internal::ObjectChain;
using internal::ResampleByArcLength;
using internal::StartCoil;
using internal::WritheContinuation;

namespace {

bool UsesUnwinding(const ScenarioSpec& spec) {
  for (const TaskSpec& t : spec.tasks) {
    if (t.target.kind == TargetKind::kUnwinding) return true;
  }
  return false;
}

// "frozen_joints": joint names or SRDF groups, held at their start values (a given start.q, else
// 0) by turning them into fixed joints of the robot; the spec's start.q and final_pose.init are
// reduced to the remaining joints (init may be given for all joints or for the remaining ones).
void FreezeScenarioJoints(const Srdf* srdf, Scenario* s) {
  ScenarioSpec& sp = s->spec;
  const Robot& robot = s->robot;
  const int n = num_dofs(robot);
  std::set<int> dofs;
  for (const std::string& name : sp.frozen_joints) {
    int joint = -1;
    for (size_t j = 0; j < robot.joints.size(); ++j) {
      if (robot.joints[j].name == name) joint = static_cast<int>(j);
    }
    if (joint >= 0) {
      if (robot.joints[joint].dof < 0) {
        throw std::invalid_argument(sp.frozen_where + ": joint '" + name + "' is fixed already");
      }
      dofs.insert(robot.joints[joint].dof);
      continue;
    }
    bool group = false;
    if (srdf != nullptr) {
      for (const SrdfGroup& g : srdf->groups) group = group || g.name == name;
    }
    if (!group) {
      std::string known;
      for (const std::string& d : DofNames(robot))
        known.append(known.empty() ? "" : ", ").append(d);
      throw std::invalid_argument(sp.frozen_where + ": '" + name +
                                  "' is neither a joint of robot '" + robot.name + "' (" + known +
                                  ") nor a group of its SRDF");
    }
    for (int k : GroupDofs(robot, *srdf, name)) dofs.insert(k);
  }
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  if (sp.start.kind == StartKind::kQ) {
    if (sp.start.q.size() != n) {
      throw std::invalid_argument(sp.start.where + ": expected " + std::to_string(n) +
                                  " numbers, got " + std::to_string(sp.start.q.size()));
    }
    q = sp.start.q;
  }
  const std::vector<std::string> names = DofNames(robot);
  for (int k : dofs) s->frozen.emplace_back(names[k], q[k]);
  const std::vector<int> kept = FreezeDofs({dofs.begin(), dofs.end()}, q, &s->robot);
  const auto reduce = [&kept](const Eigen::VectorXd& v) {
    Eigen::VectorXd r(static_cast<Eigen::Index>(kept.size()));
    for (size_t i = 0; i < kept.size(); ++i) r[static_cast<Eigen::Index>(i)] = v[kept[i]];
    return r;
  };
  if (sp.start.kind == StartKind::kQ) sp.start.q = reduce(sp.start.q);
  if (sp.final_pose.init_q.size() == n) sp.final_pose.init_q = reduce(sp.final_pose.init_q);
}

struct StartPose {
  Eigen::VectorXd q0;
  Eigen::VectorXd unwrapped;               // coil start only: the coil continued to writhe 0
  std::vector<Eigen::VectorXd> unwinding;  // coil start, "unwinding" targets: q0 continued to 0
  std::string warning;  // non-empty: the coil start collides or is outside the joint limits
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
      bool collides = false, near_line = false;
      out.q0 =
          StartCoil(s, zero, sign * wrap / 360.0, start.step, start.margin, &collides, &near_line);
      if (collides) {
        out.warning = base::StrCat(start.where, ": no collision-free start coil was found (the ",
                                   "start collides; every planner will fail on it)");
      } else {
        try {
          CheckJointValues(s.robot, out.q0, start.where);
        } catch (const std::invalid_argument& e) {
          out.warning =
              base::StrCat(e.what(), " (no start coil inside the joint limits was found; ",
                           "every planner will fail on it)");
        }
        if (out.warning.empty() && near_line) {
          out.warning = base::StrCat(
              start.where, ": no start coil clear of the pole's line beyond its ends was found (a ",
              "segment is within ", base::FormatShortest(start.margin), " m of it: a small move ",
              "passes the line there and the winding jumps)");
        }
      }
      out.unwrapped = WritheContinuation(s, zero, 0.0, start.step, start.margin);
      if (UsesUnwinding(s.spec))
        WritheContinuation(s, out.q0, 0.0, start.step, start.margin, &out.unwinding);
      break;
    }
  }
  // Planners start where the robot can be: a start outside the limits is refused (a coil start is
  // searched inside them, and the set-up warns when none was found).
  if (start.kind != StartKind::kCoil) {
    const std::string where =
        start.kind == StartKind::kZero ? "start (none given: zeros)" : start.where;
    try {
      CheckJointValues(s.robot, out.q0, where);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) + "; a plan must start inside them");
    }
  }
  return out;
}

// final_pose "init": "ik" (the default): inverse kinematics of the end targets y*_T of the
// order-0 position tasks of `fp` from q0 (16 seeded starts, collision-free); q0 when there are no
// such tasks or no start reaches them.
Eigen::VectorXd IkInit(const Scenario& s, const MotionProblem& fp, const Eigen::VectorXd& q0) {
  IkProblem problem;
  problem.seed = q0;
  for (const Task& t : fp.tasks) {
    const auto* position = dynamic_cast<const PositionFeature*>(t.feature.get());
    if (position == nullptr || t.order != 0 || t.target.cols() == 0) continue;
    IkTarget target;
    target.link = position->link();
    target.offset = position->offset();
    target.position = t.target.col(t.target.cols() - 1);
    problem.targets.push_back(target);
  }
  if (problem.targets.empty()) return q0;
  IkOptions options;
  options.starts = 16;
  options.position_tolerance = 1e-4;
  CollisionData coll(s.robot, s.initial.env, s.collision);
  KinematicsData kin(s.robot);
  options.is_valid = [&](const Eigen::VectorXd& q) {
    ForwardKinematics(s.robot, q, &kin);
    return !InCollision(s.robot, kin, &coll);
  };
  IkData data(s.robot);
  const IkResult r = SolveIk(s.robot, problem, options, &data);
  return r.status == IkStatus::kSolved ? r.q : q0;
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
      fp.tasks.push_back(BuildTask(s, s.initial, t, start.q0, nullptr));
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
  if (fps.init == FinalPoseInit::kIk) init = IkInit(s, fp, start.q0);
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
  ScenarioState& w = s->initial;
  for (const ObjectSpec& o : s->spec.objects) {
    Robot model = base::PrefixErrors(o.where + ".urdf", [&] { return LoadRobot(o.urdf); });
    const Eigen::Isometry3d pose = PoseFromXyzRpy(o.xyz, o.rpy);
    base::PrefixErrors(o.where, [&] { AddObject(model, pose, o.name, &w.objects); });
    if (!o.collide) continue;
    if (!o.capsule_chain) {
      AddObject(model, pose, o.name, &w.env);
      continue;
    }
    const int obj = static_cast<int>(w.objects.objects.size()) - 1;
    const int chain = FindIn(*o.capsule_chain, FindChain, model);
    const Eigen::Matrix3Xd pts = ObjectChainPoints(w.objects, obj, chain);
    for (Eigen::Index k = 0; k + 1 < pts.cols(); ++k) {
      const Eigen::Vector3d a = pts.col(k), b = pts.col(k + 1);
      Geometry g;
      g.kind = Geometry::Kind::kCapsule;
      g.size = Eigen::Vector3d(o.capsule_radius, (b - a).norm(), 0.0);
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = 0.5 * (a + b);
      T.linear() = RotationFromZ(b - a);
      const std::string part = o.name + "#" + std::to_string(k);
      AddObject(MakePrimitiveObject(part, g), T, part, &w.env);
    }
  }
}

void SetUpCollision(Scenario* s) {
  const CollisionSpec& c = s->spec.collision;
  s->collision.self_collision = c.self;
  s->collision.analytic_capsules = c.analytic_capsules;
  s->collision.disabled_pairs = c.disabled_pairs;
  // Every pair of links whose names start with prefixes of the same group is not checked. Each
  // prefix is non-empty (an empty one would match every link) and starts some link's name.
  const auto& robot_links = s->robot.links;
  for (size_t i = 0; i < c.disabled_groups.size(); ++i) {
    for (size_t j = 0; j < c.disabled_groups[i].size(); ++j) {
      const std::string& p = c.disabled_groups[i][j];
      const auto refuse = [&](const std::string& why) {
        throw std::invalid_argument(
            base::StrCat(c.groups_where.empty() ? "collision.disabled_groups" : c.groups_where, "[",
                         std::to_string(i), "][", std::to_string(j), "]: ", why));
      };
      if (p.empty()) refuse("empty prefix (it would match every link)");
      if (std::none_of(robot_links.begin(), robot_links.end(),
                       [&](const auto& l) { return l.name.rfind(p, 0) == 0; })) {
        std::vector<std::string> names;
        for (const auto& l : robot_links) names.push_back(l.name);
        refuse(
            base::StrCat("no link of the robot starts with '", p, "'", base::DidYouMean(p, names)));
      }
    }
  }
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
    base::PrefixErrors(c.where,
                       [&] { CollisionData check(s->robot, s->initial.env, s->collision); });
}

}  // namespace

ResolvedPoses ResolvedPosesOf(const Scenario& s) {
  return {s.initial.problem.q0, s.unwinding, s.goal_q};
}

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
  ResolveSpecFrames(&s->spec);  // world coordinates from here on
  const ScenarioSpec& sp = s->spec;
  s->initial.tasks = sp.tasks;
  s->name = sp.name;
  s->source = sp.source;
  RobotLoadOptions load;
  load.package_paths = sp.package_paths;
  const std::string robot_where = sp.robot_where.empty() ? sp.source + ": robot" : sp.robot_where;
  s->robot = base::PrefixErrors(robot_where, [&] { return LoadRobot(sp.robot, load); });
  const std::string srdf_path = sp.srdf.empty() ? FindSrdf(sp.robot, s->robot.name) : sp.srdf;
  std::optional<Srdf> srdf;
  if (!srdf_path.empty()) {
    srdf = LoadSrdf(srdf_path);
    s->warnings = CheckSrdf(*srdf, s->robot);
  }
  if (sp.start.kind == StartKind::kPose) {
    if (!srdf) throw std::invalid_argument(sp.start.where + ": a pose start needs an SRDF");
    s->spec.start.q = base::PrefixErrors(sp.start.where,
                                         [&] { return NamedPose(s->robot, *srdf, sp.start.pose); });
    s->spec.start.kind = StartKind::kQ;
  }
  if (!sp.frozen_joints.empty()) FreezeScenarioJoints(srdf ? &*srdf : nullptr, s.get());
  LoadObjects(s.get());
  for (const ChainDescription& c : sp.robot_chains) {
    s->robot.chains.push_back(ResolveChain(c, s->robot));
  }
  SetUpCollision(s.get());
  if (srdf) {
    for (const auto& pair : DisabledPairs(*srdf, &s->robot)) {
      s->collision.disabled_pairs.push_back(pair);
    }
  }
  if (sp.writhe_report) {
    s->report_chain = FindIn(sp.writhe_report->chain, FindChain, s->robot);
    s->initial.report_object_chain =
        ObjectChain(s->initial, sp.writhe_report->object, sp.writhe_report->object_chain);
  }

  StartPose start;
  if (resolved != nullptr) {
    CheckResolved(*resolved, *s);
    start.q0 = resolved->q0;
    s->unwinding = resolved->unwinding;
  } else {
    start = ResolveStart(*s, start_wrap_deg);
    if (!start.warning.empty()) s->warnings.push_back(start.warning);
    if (!start.unwinding.empty())
      s->unwinding = ResampleByArcLength(start.unwinding, sp.problem.num_steps + 1);
  }
  s->initial.problem.q0 = start.q0;
  s->start_wrap_deg = 360.0 * std::abs(ReportWritheTotal(*s, start.q0));

  s->aico = sp.aico;
  s->stop_when_solved = sp.aico_stop_when_solved;
  s->rrt = sp.rrt;
  s->rrt_goal = sp.rrt_goal;
  s->check_resolution = sp.check_resolution;
  for (const AicoAttemptSpec& a : sp.aico_attempts) {
    AicoAttempt attempt;
    attempt.max_iterations = a.max_iterations;
    attempt.init = a.init;
    if (a.init != AicoInit::kDefault && !sp.writhe_report) {
      throw std::invalid_argument(base::StrCat(
          a.init_where,
          ": the unwinding inits follow the writhe_report pair (its writhe or winding); give one"));
    }
    const Eigen::Matrix3Xd& line = s->initial.report_object_chain;
    if (a.init == AicoInit::kWindingThenReach &&
        (line.cols() < 2 || (line.col(line.cols() - 1) - line.col(0)).norm() < 1e-12)) {
      throw std::invalid_argument(base::StrCat(
          a.init_where,
          ": \"winding_then_reach\" winds the arm about the line through the ends of the "
          "writhe_report's object chain, and its ends coincide (a closed loop has no such line)"));
    }
    attempt.precision_scale = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(sp.tasks.size()));
    for (const auto& [task, factor] : a.precision_scale)
      attempt.precision_scale[TaskIndex(*s, task)] *= factor;
    s->aico_attempts.push_back(attempt);
  }

  const SuccessSpec& su = sp.success;
  s->success.writhe_total_below = su.writhe_total_below;
  s->success.writhe_closed_by_chord = su.writhe_closed_by_chord;
  if (su.position_task) s->success.position_task = TaskIndex(*s, *su.position_task);
  s->success.position_tolerance = su.position_tolerance;
  if (su.box_task) s->success.box_task = TaskIndex(*s, *su.box_task);
  if (!su.winding_where.empty() && s->report_chain < 0) {
    throw std::invalid_argument(su.winding_where + ": the winding criterion needs writhe_report");
  }
  if (su.through_loop && s->report_chain < 0) {
    throw std::invalid_argument(su.through_loop_where +
                                ": the through_loop criterion needs writhe_report");
  }
  s->success.through_loop = su.through_loop;
  s->success.winding_max_jump = su.winding_max_jump;
  s->success.winding_final_below = su.winding_final_below;
  s->success.winding_closed_by_chord = su.winding_closed_by_chord;
  s->success.winding_tunnel_through_object_only = su.winding_tunnel_through_object_only;

  // The goal's end conditions read the position/box targets of a problem built with goal q0.
  s->goal_q = start.q0;
  s->initial.problem = AttemptProblem(*s, 0);
  s->goal_q = resolved != nullptr ? resolved->goal_q : EstimateGoal(*s, start);
  s->initial.problem = AttemptProblem(*s, 0);
  return s;
}

}  // namespace planning
