#include "app/session.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "app/assets.h"
#include "app/grasp_inputs.h"
#include "planning/grasp_transfer.h"
#include "planning/physics/grasp_trials.h"
#include "planning/physics/ode_runtime.h"
#include "topology/input_limits.h"

namespace app {
namespace {

// A JSON file with a "tasks" array is a planning scenario; anything else LoadRobotScene takes.
bool IsPlanningScenario(const std::string& path) {
  if (path.size() < 5 || path.substr(path.size() - 5) != ".json") return false;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  return j.is_object() && j.contains("tasks");
}

}  // namespace

const planning::Robot& Session::robot() const {
  if (scenario_) return scenario_->robot;
  if (robot_scene_) return robot_scene_->robot;
  throw std::logic_error("Session: nothing loaded");
}

const planning::Environment& Session::objects() const {
  if (scenario_) return scenario_->objects;
  if (robot_scene_) return robot_scene_->env;
  throw std::logic_error("Session: nothing loaded");
}

std::vector<std::string> Session::joint_names() const { return planning::DofNames(robot()); }

void Session::Load(const std::string& arg, const Settings& settings) {
  const std::string path = ResolveScenarioPath(arg);
  result_.reset();
  sweeps_.clear();
  rrt_trees_.clear();
  ++plan_version_;
  if (IsPlanningScenario(path)) {
    planning::ScenarioOverrides overrides;
    if (settings.planner.start_wrap_deg >= 0) {
      overrides.start_wrap_deg = settings.planner.start_wrap_deg;
    }
    overrides.package_paths = PackagePaths(settings.robot_input.package_paths);
    overrides.srdf = settings.robot_input.srdf;
    scenario_ = LoadScenarioArg(path, overrides);
    robot_scene_.reset();
    joint_q_ = scenario_->problem.q0;
    status_ = "loaded scenario " + scenario_->name;
  } else {
    robot_scene_ = LoadRobotScene(path, settings.robot_input);
    scenario_.reset();
    joint_q_ = robot_scene_->q;
    status_ = "loaded " + path;
  }
}

// What a plan (or re-plan) job hands to the draw thread. The job appends under `mutex`; the draw
// thread copies what is new in Poll(). `result` and `scenario` are set once, at the job's end.
struct Session::PlanOutput {
  std::mutex mutex;
  std::vector<SweepRecord> sweeps;
  std::optional<planning::PlanResult> result;
  std::shared_ptr<planning::Scenario> scenario;  // re-plan after a move: the moved scenario
  std::vector<RrtTreeView> trees;                // RRT plans: the trees so far
  long rrt_checks = 0;
  bool finished = false;
  bool stepped = false;  // started by kStep: keep showing the last slice
  bool follow = true;    // show each new sweep (a re-plan keeps playing the old trajectory)
  std::string what = "plan", error;
};

// What the live ODE simulation hands to the draw thread (frames appended under `mutex`).
struct Session::GraspOutput {
  std::mutex mutex;
  GraspReplay replay;
  bool started = false;  // hand and object are set
  bool finished = false;
  bool stepped = false;  // started by kSimStep: keep showing the newest frame at the end
  std::string error;
};

namespace {

// Runs `job` and records in `out` (under its mutex) that it ended, also when it throws.
template <typename Output, typename Fn>
void RunRecordingEnd(Output* out, Fn&& job) {
  try {
    job();
  } catch (const Worker::Cancelled&) {
    std::lock_guard<std::mutex> lock(out->mutex);
    out->finished = true;
    throw;
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(out->mutex);
    out->finished = true;
    out->error = e.what();
    throw;
  }
  std::lock_guard<std::mutex> lock(out->mutex);
  out->finished = true;
}

}  // namespace

std::shared_ptr<Session::PlanOutput> Session::NewPlanJob(long budget, const char* stepped_name,
                                                         Worker::Job* job) {
  auto out = std::make_shared<PlanOutput>();
  out->stepped = budget >= 0;
  plan_out_ = out;
  job->name = budget >= 0 ? stepped_name : "plan";
  job->budget = budget;
  return out;
}

void Session::DropJob() {
  worker_.Cancel();
  plan_out_.reset();
  if (grasp_out_) {
    grasp_out_.reset();
    if (grasp_) grasp_->finished = true;  // what was simulated stays as a replay
  }
}

void Session::StartPlan(Settings* settings, long budget) {
  if (!scenario_) throw std::invalid_argument("plan: the loaded file is not a planning scenario");
  const planning::Planner planner = planning::ParsePlanner(settings->planner.planner);
  // The solver options come from the settings (what the planner panel edits). A cancelled job
  // may still read them until its next sweep: wait for it only when they change.
  planning::AicoOptions& a = scenario_->aico;
  if (a.max_iterations != settings->planner.max_iterations ||
      a.tolerance != settings->planner.tolerance || a.damping != settings->planner.damping) {
    worker_.Wait(/*join_parked=*/true);
    a.max_iterations = settings->planner.max_iterations;
    a.tolerance = settings->planner.tolerance;
    a.damping = settings->planner.damping;
  }
  sweeps_.clear();
  result_.reset();
  rrt_trees_.clear();
  rrt_checks_ = 0;
  ++plan_version_;
  settings->sweep = -1;
  settings->frame = 0;
  if (planner == planning::Planner::kRrt || planner == planning::Planner::kBiRrt) {
    StartRrt(settings, budget);
    return;
  }
  Worker::Job job;
  const std::shared_ptr<PlanOutput> out = NewPlanJob(budget, "step", &job);
  std::shared_ptr<const planning::Scenario> scenario = scenario_;
  const unsigned seed = settings->planner.seed;
  job.run = [out, scenario, planner, seed](Worker& worker) {
    RunRecordingEnd(out.get(), [&] {
      planning::AicoCallback record;
      if (planner == planning::Planner::kAico) {
        record = [&](int sweep, double cost, bool accepted, const planning::Trajectory& t) {
          {
            std::lock_guard<std::mutex> lock(out->mutex);
            out->sweeps.push_back({sweep, cost, accepted, t.q});
          }
          worker.Checkpoint();
        };
      }
      planning::PlanResult r = planning::RunPlanner(*scenario, planner, seed, record);
      std::lock_guard<std::mutex> lock(out->mutex);
      out->result = std::move(r);
    });
  };
  worker_.Submit(std::move(job));
  status_ = std::string(planning::PlannerName(planner)) + ": planning ...";
}

namespace {

// The link whose origin stands for a configuration in the RRT tree view.
int GraspPointLink(const planning::Robot& robot) {
  for (int i = 0; i < static_cast<int>(robot.links.size()); ++i) {
    if (robot.links[i].name == "sdh_grasp_link") return i;
  }
  return static_cast<int>(robot.links.size()) - 1;
}

}  // namespace

void Session::StartRrt(Settings* settings, long budget) {
  const planning::Planner planner = planning::ParsePlanner(settings->planner.planner);
  Worker::Job job;
  const std::shared_ptr<PlanOutput> out = NewPlanJob(budget, "rrt_step", &job);
  std::shared_ptr<const planning::Scenario> scenario = scenario_;
  const unsigned seed = settings->planner.seed;
  job.run = [out, scenario, planner, seed](Worker& worker) {
    RunRecordingEnd(out.get(), [&] {
      const planning::Scenario& s = *scenario;
      // The RRT set-up of RunPlanner (planning/planner.h).
      planning::CollisionData coll(s.robot, s.env, s.collision);
      planning::KinematicsData kin(s.robot), fk(s.robot);
      const planning::RrtProblem rp = planning::ScenarioRrtProblem(s);
      const planning::ValidityFn valid = planning::ValidityChecker(s, &coll, &kin);
      planning::RrtSolver solver(rp, s.rrt, valid, std::mt19937(seed),
                                 planner == planning::Planner::kBiRrt);
      const int link = GraspPointLink(s.robot);
      const auto publish = [&] {
        std::lock_guard<std::mutex> lock(out->mutex);
        out->trees.resize(solver.num_trees());
        for (int i = 0; i < solver.num_trees(); ++i) {
          const std::vector<planning::RrtNode>& nodes = solver.tree(i);
          RrtTreeView& view = out->trees[i];
          for (size_t k = view.points.size(); k < nodes.size(); ++k) {
            planning::ForwardKinematics(s.robot, nodes[k].q, &fk);
            view.points.push_back(fk.world_from_link[link].translation());
            view.parents.push_back(nodes[k].parent);
          }
        }
        out->rrt_checks = solver.checks();
      };
      publish();
      while (!solver.done()) {
        solver.Step(1);
        publish();
        worker.Checkpoint();
      }
      planning::PlanResult r;
      r.trajectory = solver.result().path;
      planning::PlanReport& rep = r.report;
      rep.planner = planning::PlannerName(planner);
      rep.status = solver.status();
      rep.iterations = solver.iterations();
      rep.collision_checks = coll.queries;
      rep.start_writhe_total = planning::ReportWritheTotal(s, s.problem.q0);
      rep.final_writhe_total = rep.start_writhe_total;
      if (r.trajectory.num_points() > 0) {
        const planning::PlanVerdict v = planning::JudgePlan(s, r.trajectory);
        rep.failure_reason = v.reason;
        rep.final_writhe_total = v.final_writhe_total;
        rep.success = rep.status == planning::SolveStatus::kConverged &&
                      v.reason == planning::FailureReason::kNone;
      } else {
        rep.failure_reason = planning::FailureReason::kBudgetExhausted;
      }
      std::lock_guard<std::mutex> lock(out->mutex);
      out->result = std::move(r);
    });
  };
  worker_.Submit(std::move(job));
  status_ = std::string(planning::PlannerName(planner)) + ": growing the trees ...";
}

void Session::ShowPlanResult(Settings* settings) {
  const planning::PlanReport& r = result_->report;
  std::ostringstream msg;
  msg << r.planner << ": " << (r.success ? "success" : "FAILED") << ", " << r.collision_checks
      << " collision checks, " << r.iterations << " iterations, writhe " << r.start_writhe_total
      << " -> " << r.final_writhe_total;
  status_ = msg.str();
  settings->sweep = -1;
  settings->frame = plan_out_ && plan_out_->stepped ? std::max(0, num_frames(*settings) - 1) : 0;
}

void Session::StartMove(const SessionCommand& c, Settings* settings) {
  if (!scenario_) throw std::invalid_argument("move: the loaded file is not a planning scenario");
  planning::ScenarioSpec spec = scenario_->spec;
  std::vector<std::string> names;
  planning::ObjectSpec* object = nullptr;
  for (planning::ObjectSpec& o : spec.objects) {
    names.push_back(o.name);
    if (o.name == c.text) object = &o;
  }
  if (object == nullptr) {
    throw std::invalid_argument("move: no object '" + c.text + "' " + ValidChoices(names));
  }
  if (!c.position.allFinite()) throw std::invalid_argument("move: position is not finite");
  object->xyz = c.position;
  // Receding horizon: re-plan from the configuration shown now, warm-started with the rest of
  // the shown trajectory (shifted to start now, its last slice repeated).
  const Eigen::VectorXd q_now = ShownQ(*settings);
  std::optional<Eigen::MatrixXd> init;
  const int n = num_frames(*settings);
  const int T1 = scenario_->problem.num_steps + 1;
  if (n == T1 && planning::ParsePlanner(settings->planner.planner) == planning::Planner::kAico) {
    const Eigen::MatrixXd& q =
        settings->sweep >= 0 ? sweeps_[settings->sweep].q : result_->trajectory.q;
    const int from = std::clamp(settings->frame, 0, n - 1);
    init = Eigen::MatrixXd(q.rows(), T1);
    for (int t = 0; t < T1; ++t) init->col(t) = q.col(std::min(n - 1, from + t));
    init->col(0) = q_now;
  }
  std::optional<double> wrap;
  if (settings->planner.start_wrap_deg >= 0) wrap = settings->planner.start_wrap_deg;
  const planning::AicoOptions aico = scenario_->aico;
  const unsigned seed = settings->planner.seed;
  const planning::Planner planner = planning::ParsePlanner(settings->planner.planner);
  DropJob();
  sweeps_.clear();
  ++plan_version_;
  auto out = std::make_shared<PlanOutput>();
  out->what = "re-plan after moving " + c.text;
  out->follow = false;
  plan_out_ = out;
  Worker::Job job;
  job.name = "move";
  job.run = [out, spec = std::move(spec), wrap, aico, q_now, init, seed, planner](Worker& worker) {
    RunRecordingEnd(out.get(), [&] {
      std::shared_ptr<planning::Scenario> moved = planning::SetUpScenario(spec, wrap);
      moved->aico.max_iterations = aico.max_iterations;
      moved->aico.tolerance = aico.tolerance;
      moved->aico.damping = aico.damping;
      worker.Checkpoint();
      const auto record = [&](int sweep, double cost, bool accepted,
                              const planning::Trajectory& t) {
        {
          std::lock_guard<std::mutex> lock(out->mutex);
          out->sweeps.push_back({sweep, cost, accepted, t.q});
        }
        worker.Checkpoint();
      };
      planning::PlanResult r;
      if (init && init->rows() == moved->problem.q0.size()) {
        moved->problem.q0 = q_now;
        planning::AicoWorkspace ws(moved->problem);
        planning::Trajectory warm{*init, planning::tau(moved->problem)};
        const planning::AicoResult a = planning::SolveAico(
            moved->problem, planning::AttemptOptions(*moved, 0), &ws, record, &warm);
        r.trajectory = a.trajectory;
        planning::PlanReport& rep = r.report;
        rep.planner = "aico (warm start)";
        rep.status = a.status;
        rep.iterations = a.iterations;
        rep.cost = a.cost;
        rep.cost_history = a.cost_history;
        rep.collision_checks = a.collision_queries;
        rep.start_writhe_total = planning::ReportWritheTotal(*moved, q_now);
        const planning::PlanVerdict v = planning::JudgePlan(*moved, a.trajectory);
        rep.failure_reason = v.reason;
        rep.success = v.reason == planning::FailureReason::kNone;
        rep.final_writhe_total = v.final_writhe_total;
        rep.reach_error_m = v.reach_error_m;
      } else {
        r = planning::RunPlanner(*moved, planner, seed, record);
      }
      std::lock_guard<std::mutex> lock(out->mutex);
      out->result = std::move(r);
      out->scenario = std::move(moved);
    });
  };
  worker_.Submit(std::move(job));
  status_ = "moved " + c.text + ": re-planning ...";
}

void Session::StartGrasp(Settings* settings, long budget) {
  namespace phys = planning::physics;
  const std::string name = settings->grasp.grasp;
  const planning::TransferMethod method = planning::ParseTransferMethod(settings->grasp.method);
  auto in =
      std::make_shared<const GraspInputs>(LoadGraspInputs({AssetPath("grasps/" + name + ".json")}));
  DropJob();
  auto out = std::make_shared<GraspOutput>();
  out->replay.grasp = name;
  out->replay.method = settings->grasp.method;
  out->stepped = budget >= 0;
  grasp_out_ = out;
  grasp_.reset();
  Worker::Job job;
  job.name = "grasp";
  job.budget = budget;
  job.run = [out, in, method](Worker& worker) {
    RunRecordingEnd(out.get(), [&] {
      const int stride = out->replay.stride;
      phys::GraspTrialHooks hooks;
      int step = 0;
      hooks.on_start = [&](const planning::TransferSetup&, const planning::TransferResult&,
                           const phys::SimHand& hand,
                           const phys::SimObject& object) -> phys::StepCallback {
        {
          std::lock_guard<std::mutex> lock(out->mutex);
          out->replay.hand = hand;
          out->replay.object = object;
          out->started = true;
        }
        return [&](int phase, const phys::GraspSimulation& sim) {
          // Every stride-th step, and the state a stepped run holds at.
          if (step++ % stride == 0 || worker.AtBudget()) {
            std::lock_guard<std::mutex> lock(out->mutex);
            out->replay.frames.push_back({phase, sim.state()});
          }
          worker.Checkpoint();
        };
      };
      phys::OdeRuntime ode;
      phys::GraspTrialsResult trials =
          phys::RunGraspTrials(ode, in->human, in->lwr_sdh, in->objects, in->grasps, {method},
                               phys::StabilityOptions{}.sim.mu, hooks);
      phys::GraspTrial& trial = trials.trials.at(0).at(0);
      std::lock_guard<std::mutex> lock(out->mutex);
      out->replay.result = std::move(trial.stability);
      out->replay.winding_error = trial.winding_error;
      out->replay.finished = true;
    });
  };
  worker_.Submit(std::move(job));
  settings->grasp.active = true;
  settings->grasp.frame = 0;
  settings->camera_initialised = false;
  status_ = name + " (" + settings->grasp.method + "): simulating ...";
}

void Session::Poll(Settings* settings) {
  worker_.Collect();
  if (const std::shared_ptr<PlanOutput> out = plan_out_) {
    std::unique_lock<std::mutex> lock(out->mutex);
    const size_t had = sweeps_.size();
    for (size_t k = had; k < out->sweeps.size(); ++k) sweeps_.push_back(out->sweeps[k]);
    if (sweeps_.size() != had) {
      ++plan_version_;
      if (!out->result && out->follow) {  // show the newest sweep, its last slice
        settings->sweep = static_cast<int>(sweeps_.size()) - 1;
        settings->frame = std::max(0, num_frames(*settings) - 1);
        const SweepRecord& s = sweeps_.back();
        std::ostringstream msg;
        msg << out->what << ": sweep " << s.sweep + 1 << " of " << settings->planner.max_iterations
            << ", cost " << s.cost << (s.accepted ? " (accepted)" : " (rejected)");
        status_ = msg.str();
      }
    }
    if (!out->trees.empty()) {
      rrt_trees_.resize(out->trees.size());
      long nodes = 0;
      for (size_t i = 0; i < out->trees.size(); ++i) {
        const RrtTreeView& from = out->trees[i];
        RrtTreeView& to = rrt_trees_[i];
        for (size_t k = to.points.size(); k < from.points.size(); ++k) {
          to.points.push_back(from.points[k]);
          to.parents.push_back(from.parents[k]);
        }
        nodes += static_cast<long>(to.points.size());
      }
      if (rrt_checks_ != out->rrt_checks && !out->result) {
        std::ostringstream msg;
        msg << out->what << ": " << nodes << " nodes, " << out->rrt_checks << " checks";
        status_ = msg.str();
      }
      rrt_checks_ = out->rrt_checks;
    }
    if (out->finished) {
      std::optional<planning::PlanResult> result = std::move(out->result);
      std::shared_ptr<planning::Scenario> moved = std::move(out->scenario);
      const std::string error = out->error, what = out->what;
      lock.unlock();
      if (moved) {
        scenario_ = std::move(moved);
        joint_q_ = scenario_->problem.q0;
      }
      if (result) {
        result_ = std::move(result);
        ++plan_version_;
        ShowPlanResult(settings);
      } else {
        status_ = error.empty() ? what + " cancelled after " + std::to_string(sweeps_.size()) +
                                      " sweeps (no result)"
                                : "error: " + error;
      }
      plan_out_.reset();
    }
  }
  if (const std::shared_ptr<GraspOutput> out = grasp_out_) {
    std::lock_guard<std::mutex> lock(out->mutex);
    if (out->started && !grasp_) {
      grasp_ = GraspReplay();
      grasp_->grasp = out->replay.grasp;
      grasp_->method = out->replay.method;
      grasp_->hand = out->replay.hand;
      grasp_->object = out->replay.object;
      settings->camera_initialised = false;  // frame the hand once it is there
    }
    if (grasp_) {
      const size_t had = grasp_->frames.size();
      for (size_t k = had; k < out->replay.frames.size(); ++k) {
        grasp_->frames.push_back(out->replay.frames[k]);
      }
      if (grasp_->frames.size() != had) {
        settings->grasp.frame = static_cast<int>(grasp_->frames.size()) - 1;
        std::ostringstream msg;
        msg << grasp_->grasp << " (" << grasp_->method << "): simulated "
            << grasp_->frames.back().state.time << " s";
        status_ = msg.str();
      }
    }
    if (out->finished) {
      if (grasp_ && out->replay.finished) {
        grasp_->result = out->replay.result;
        grasp_->winding_error = out->replay.winding_error;
        grasp_->finished = true;
        if (!out->stepped) {  // a finished test replays from its start, framed on it
          settings->grasp.frame = 0;
          settings->camera_initialised = false;
        }
        std::ostringstream msg;
        msg << grasp_->grasp << " (" << grasp_->method << "): " << grasp_->result.directions_passed
            << "/6 gravity directions held, "
            << (grasp_->result.stable ? "stable"
                                      : planning::physics::ToString(grasp_->result.status))
            << ", " << grasp_->frames.size() << " frames";
        status_ = msg.str();
      } else {
        if (grasp_) grasp_->finished = true;
        status_ = out->error.empty() ? "simulation cancelled" : "error: " + out->error;
      }
      grasp_out_.reset();
    }
  }
}

bool Session::settled() const {
  if (worker_.parked()) return true;
  return !worker_.busy() && !plan_out_ && !grasp_out_;
}

void Session::Wait(Settings* settings) {
  worker_.Wait();
  Poll(settings);
}

Session::~Session() {
  worker_.Cancel();
  worker_.Wait(/*join_parked=*/true);
}

WorkerStatus Session::worker_status(const Settings& settings) const {
  WorkerStatus w;
  w.job = worker_.job_name();
  w.computing = worker_.computing();
  w.held = worker_.parked();
  w.sweep = static_cast<int>(sweeps_.size());
  w.max_sweeps = settings.planner.max_iterations;
  if (!sweeps_.empty()) w.cost = sweeps_.back().cost;
  if (result_) w.cost = result_->report.cost;
  if (scenario_) w.rrt_budget = scenario_->rrt.max_checks;
  for (const RrtTreeView& t : rrt_trees_) w.rrt_nodes += static_cast<long>(t.points.size());
  w.rrt_checks = rrt_checks_;
  if (grasp_ && !grasp_->frames.empty()) {
    const int f = std::clamp(settings.grasp.frame, 0, static_cast<int>(grasp_->frames.size()) - 1);
    w.sim_time_s = grasp_->frames[f].state.time;
  }
  return w;
}

Eigen::Vector3d Session::GraspGravity(int frame) const {
  if (!grasp_ || grasp_->frames.empty()) return Eigen::Vector3d::Zero();
  const GraspReplay::Frame& f =
      grasp_->frames[std::clamp<size_t>(frame, 0, grasp_->frames.size() - 1)];
  if (f.phase < 1 || f.phase > static_cast<int>(grasp_->result.directions.size())) {
    return Eigen::Vector3d::Zero();
  }
  const Eigen::Matrix3d world_from_palm = f.state.world_from_link.at(0).linear();
  return world_from_palm * grasp_->result.directions[f.phase - 1].gravity_palm;
}

void Session::Apply(const SessionCommand& c, Settings* settings) {
  using K = SessionCommand::Kind;
  const auto count = [&](const char* verb) {
    const double n = c.value == 0.0 ? 1.0 : c.value;
    if (!(n >= 1 && n <= 1e6) || n != std::floor(n)) {
      std::ostringstream msg;
      msg << verb << ": N must be an integer in [1, 1000000], got " << c.value;
      throw std::invalid_argument(msg.str());
    }
    return static_cast<long>(n);
  };
  switch (c.kind) {
    case K::kGraspRun:
      StartGrasp(settings, -1);
      return;
    case K::kSimStep: {
      const long n = count("sim_step");
      if (!grasp_out_ || !worker_.AddBudget(n)) StartGrasp(settings, n);
      return;
    }
    case K::kGraspStep: {
      if (!grasp_) throw std::invalid_argument("grasp_step: no simulation yet (run 'grasp' first)");
      const int n = static_cast<int>(grasp_->frames.size());
      settings->grasp.active = true;
      settings->grasp.frame =
          std::clamp(settings->grasp.frame + static_cast<int>(c.value), 0, std::max(0, n - 1));
      return;
    }
    case K::kLoad:
      DropJob();
      Load(c.text, *settings);
      settings->scenario_path = c.text;
      settings->sweep = -1;
      settings->frame = 0;
      settings->playing = false;
      settings->camera_initialised = false;
      return;
    case K::kPlan:
      DropJob();
      StartPlan(settings, -1);
      settings->playing = false;
      Wait(settings);
      return;
    case K::kPlanAsync:
      DropJob();
      StartPlan(settings, -1);
      settings->playing = false;
      return;
    case K::kStep: {
      const long n = count("step");
      settings->playing = false;
      if (plan_out_ && worker_.parked() && worker_.job_name() == "step" && worker_.AddBudget(n)) {
        return;
      }
      if (plan_out_ && worker_.computing()) {
        throw std::invalid_argument("step: a plan is running (cancel it, or wait for it first)");
      }
      if (plan_out_ && worker_.parked() && worker_.job_name() != "step") DropJob();
      if (planning::ParsePlanner(settings->planner.planner) != planning::Planner::kAico) {
        throw std::invalid_argument("step: steps AICO sweeps; the planner is '" +
                                    settings->planner.planner +
                                    "' (valid: aico; rrt_step grows "
                                    "rrt/birrt trees)");
      }
      DropJob();
      StartPlan(settings, n);
      return;
    }
    case K::kCancel:
      worker_.Cancel();
      return;
    case K::kRrtStep: {
      const long n = count("rrt_step");
      settings->playing = false;
      if (plan_out_ && worker_.parked() && worker_.job_name() == "rrt_step" &&
          worker_.AddBudget(n)) {
        return;
      }
      const planning::Planner p = planning::ParsePlanner(settings->planner.planner);
      if (p != planning::Planner::kRrt && p != planning::Planner::kBiRrt) {
        throw std::invalid_argument("rrt_step: grows RRT/BiRRT trees; the planner is '" +
                                    settings->planner.planner + "' (valid: rrt, birrt)");
      }
      DropJob();
      StartPlan(settings, n);
      return;
    }
    case K::kMove:
      StartMove(c, settings);
      return;
    case K::kPlay:
      if (settings->frame >= num_frames(*settings) - 1) settings->frame = 0;
      settings->playing = num_frames(*settings) > 1;
      return;
    case K::kPause:
      settings->playing = false;
      return;
    case K::kSeek: {
      const int n = num_frames(*settings);
      const double dt = ShownDt(*settings);
      const double slice = std::round(c.value / dt);
      settings->frame = n == 0 ? 0 : static_cast<int>(std::clamp(slice, 0.0, n - 1.0));
      return;
    }
    case K::kSetJoint: {
      if (!loaded()) throw std::invalid_argument("joint: nothing loaded");
      if (c.index < 0 || c.index >= joint_q_.size()) {
        throw std::invalid_argument("joint: index " + std::to_string(c.index) +
                                    " out of range 0.." + std::to_string(joint_q_.size() - 1));
      }
      if (num_frames(*settings) > 0) joint_q_ = ShownQ(*settings);
      joint_q_(c.index) = c.value;
      DropJob();
      result_.reset();
      sweeps_.clear();
      ++plan_version_;
      settings->sweep = -1;
      settings->frame = 0;
      settings->playing = false;
      return;
    }
    case K::kReset:
      DropJob();
      if (scenario_) joint_q_ = scenario_->problem.q0;
      if (robot_scene_) joint_q_ = robot_scene_->q;
      result_.reset();
      sweeps_.clear();
      rrt_trees_.clear();
      ++plan_version_;
      settings->sweep = -1;
      settings->frame = 0;
      settings->playing = false;
      status_ = "reset";
      return;
  }
}

double Session::ShownDt(const Settings& settings) const {
  const bool sweep = settings.sweep >= 0 && settings.sweep < static_cast<int>(sweeps_.size());
  if (!sweep && result_ && result_->trajectory.dt > 0) return result_->trajectory.dt;
  if (scenario_) return planning::tau(scenario_->problem);
  return 1.0;
}

double Session::HeatmapLimit(const Settings& settings) const {
  const std::pair<long, int> key(plan_version_, settings.sweep);
  if (heatmap_key_ != key || heatmap_limit_ <= 0) {
    const int n = num_frames(settings);
    double limit = 0.0;
    Settings at = settings;
    for (int f = 0; f < std::max(1, n); ++f) {
      at.frame = f;
      const Eigen::MatrixXd w = WritheAt(ShownQ(at));
      if (w.size() > 0) limit = std::max(limit, w.cwiseAbs().maxCoeff());
    }
    heatmap_key_ = n > 0 ? key : std::pair<long, int>(-1, 0);
    heatmap_limit_ = std::max(1e-9, limit);
  }
  return heatmap_limit_;
}

void Session::Tick(Settings* settings) const {
  if (!settings->playing) return;
  const int n = num_frames(*settings);
  settings->frame += std::max(1, settings->play_stride);
  if (settings->frame >= n - 1) {
    settings->frame = std::max(0, n - 1);
    settings->playing = false;
  }
}

int Session::num_frames(const Settings& settings) const {
  if (settings.sweep >= 0 && settings.sweep < static_cast<int>(sweeps_.size())) {
    return static_cast<int>(sweeps_[settings.sweep].q.cols());
  }
  if (result_) return result_->trajectory.num_points();
  return 0;
}

Eigen::VectorXd Session::ShownQ(const Settings& settings) const {
  const int n = num_frames(settings);
  if (n == 0) return joint_q_;
  const int f = std::clamp(settings.frame, 0, n - 1);
  if (settings.sweep >= 0 && settings.sweep < static_cast<int>(sweeps_.size())) {
    return sweeps_[settings.sweep].q.col(f);
  }
  return result_->trajectory.q.col(f);
}

Eigen::MatrixXd Session::WritheAt(const Eigen::VectorXd& q) const {
  if (!scenario_ || scenario_->report_chain < 0) return {};
  Eigen::MatrixXd w;
  planning::ReportWritheTotal(*scenario_, q, &w);
  return w;
}

namespace {

struct VerbSpec {
  const char* verb;
  int min_args, max_args;
  const char* usage;
};

// Every script verb with its argument counts and usage.
const std::vector<VerbSpec>& ScriptVerbs() {
  static const std::vector<VerbSpec> kVerbs = {
      {"load", 1, 1, "load PATH"},
      {"plan", 0, 1, "plan [async]"},
      {"step", 0, 1, "step [N]"},
      {"wait", 0, 0, "wait"},
      {"cancel", 0, 0, "cancel"},
      {"rrt_step", 1, 1, "rrt_step N"},
      {"sim_step", 1, 1, "sim_step N"},
      {"move", 4, 4, "move OBJECT X Y Z"},
      {"status", 1, 1, "status FILE"},
      {"play", 0, 0, "play"},
      {"pause", 0, 0, "pause"},
      {"seek", 1, 1, "seek SECONDS"},
      {"joint", 2, 2, "joint INDEX ANGLE"},
      {"reset", 0, 0, "reset"},
      {"toggle", 1, 1, "toggle NAME"},
      {"planner", 1, 1, "planner NAME"},
      {"seed", 1, 1, "seed N"},
      {"camera", 3, 6, "camera YAW PITCH DISTANCE [TX TY TZ]"},
      {"frames", 1, 1, "frames N"},
      {"screenshot", 1, 1, "screenshot PATH"},
      {"click", 1, 1, "click WIDGET"},
      {"grasp", 2, 2, "grasp NAME METHOD"},
      {"grasp_step", 1, 1, "grasp_step N"},
      {"quit", 0, 0, "quit"}};
  return kVerbs;
}

// The arguments of a script line, checked when the script is read (the viewer converts them
// later): "frames" an integer in [1, kMaxScriptFrames] (and all frames lines together at most
// kMaxScriptTotalFrames), "seed" an integer in [0, 2^32 − 1], step/rrt_step/sim_step N in
// [1, 1e6], "joint" an index in [0, 1e6] and a finite value, camera/seek/grasp_step/move finite
// numbers that fit a float; names from their fixed lists.
void CheckScriptArgs(const std::string& path, const ScriptLine& l, long long* total_frames) {
  const std::string at = path + ":" + std::to_string(l.line) + ": ";
  const auto where = [&](size_t i) { return at + "'" + l.args[i] + "'"; };
  const auto number = [&](size_t i, double lo, double hi) {
    const std::optional<double> v = topology::ParseFiniteDouble(l.args[i]);
    if (!v) throw std::invalid_argument(where(i) + " is not a finite number");
    if (*v < lo || *v > hi) {
      std::ostringstream range;
      range << "[" << lo << ", " << hi << "]";
      throw std::invalid_argument(where(i) + " is out of range " + range.str());
    }
    return *v;
  };
  const auto integer = [&](size_t i, double lo, double hi) {
    const double v = number(i, lo, hi);
    if (v != std::floor(v)) throw std::invalid_argument(where(i) + " is not an integer");
    return static_cast<long long>(v);
  };
  const auto one_of = [&](size_t i, const char* what, const std::vector<std::string>& choices) {
    if (std::find(choices.begin(), choices.end(), l.args[i]) == choices.end()) {
      throw std::invalid_argument(at + "unknown " + what + " '" + l.args[i] + "' " +
                                  ValidChoices(choices));
    }
  };
  if (l.verb == "frames") {
    *total_frames += integer(0, 1, kMaxScriptFrames);
    if (*total_frames > kMaxScriptTotalFrames) {
      throw std::invalid_argument(at + "more than " + std::to_string(kMaxScriptTotalFrames) +
                                  " frames in the script (limit)");
    }
  } else if (l.verb == "seed") {
    integer(0, 0, 4294967295.0);
  } else if (l.verb == "joint") {
    integer(0, 0, 1e6);
    number(1, -1e6, 1e6);
  } else if (l.verb == "camera") {
    if (l.args.size() != 3 && l.args.size() != 6) {
      throw std::invalid_argument(
          at + "'camera' takes 3 or 6 arguments: " + "camera YAW PITCH DISTANCE [TX TY TZ]");
    }
    number(0, -1e6, 1e6);
    number(1, -1e6, 1e6);
    number(2, 1e-6, 1e6);
    for (size_t i = 3; i < l.args.size(); ++i) number(i, -1e6, 1e6);
  } else if (l.verb == "seek" || l.verb == "grasp_step") {
    number(0, -1e9, 1e9);
  } else if (l.verb == "step" || l.verb == "rrt_step" || l.verb == "sim_step") {
    if (!l.args.empty()) integer(0, 1, 1e6);
  } else if (l.verb == "move") {
    for (size_t i = 1; i < 4; ++i) number(i, -1e6, 1e6);
  } else if (l.verb == "plan") {
    if (!l.args.empty()) one_of(0, "plan mode", {"async"});
  } else if (l.verb == "toggle") {
    one_of(0, "toggle", ScriptToggles());
  } else if (l.verb == "planner") {
    std::vector<std::string> names;
    for (planning::Planner p : planning::AvailablePlanners()) {
      names.push_back(planning::PlannerName(p));
    }
    one_of(0, "planner", names);
  } else if (l.verb == "grasp") {
    one_of(1, "transfer method", {"winding", "joint", "fingertip"});
  }
}

}  // namespace

std::string ValidChoices(const std::vector<std::string>& choices) {
  std::string s = "(valid: ";
  for (size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
  return s + ")";
}

const std::vector<std::string>& ScriptToggles() {
  static const std::vector<std::string> kToggles = {"chains",   "collision", "grid",
                                                    "contacts", "heatmap",   "cost"};
  return kToggles;
}

std::vector<ScriptLine> ParseScript(const std::string& path) {
  std::istringstream in(topology::ReadFileBounded(path, "script"));
  const std::vector<VerbSpec>& verbs = ScriptVerbs();
  std::vector<ScriptLine> lines;
  std::string raw;
  int n = 0;
  long long total_frames = 0;
  while (std::getline(in, raw)) {
    ++n;
    std::istringstream ss(raw);
    ScriptLine l;
    l.file = path;
    l.line = n;
    if (!(ss >> l.verb) || l.verb[0] == '#') continue;
    for (std::string a; ss >> a;) l.args.push_back(a);
    const auto it = std::find_if(verbs.begin(), verbs.end(),
                                 [&](const VerbSpec& v) { return v.verb == l.verb; });
    const std::string at = path + ":" + std::to_string(n) + ": ";
    if (it == verbs.end()) {
      std::vector<std::string> names;
      for (const VerbSpec& v : verbs) names.push_back(v.verb);
      throw std::invalid_argument(at + "unknown command '" + l.verb + "' " + ValidChoices(names));
    }
    const int argc = static_cast<int>(l.args.size());
    if (argc < it->min_args || argc > it->max_args) {
      const std::string count =
          it->min_args == it->max_args
              ? std::to_string(it->min_args)
              : std::to_string(it->min_args) + " to " + std::to_string(it->max_args);
      throw std::invalid_argument(at + "'" + l.verb + "' takes " + count + " argument(s), got " +
                                  std::to_string(argc) + ": " + it->usage);
    }
    CheckScriptArgs(path, l, &total_frames);
    lines.push_back(std::move(l));
  }
  return lines;
}

void WriteStatusJson(const std::string& path, const std::string& planner, const WorkerStatus& st,
                     const std::vector<double>& frame_ms, long frames_while_planning) {
  nlohmann::json j;
  j["planner"] = planner;
  j["planning"] = st.computing && st.job != "grasp";  // plan, step, rrt_step, move
  j["held"] = st.held;
  j["job"] = st.job;
  j["sweep"] = st.sweep;
  j["max_sweeps"] = st.max_sweeps;
  j["cost"] = st.cost;
  j["rrt_nodes"] = st.rrt_nodes;
  j["rrt_checks"] = st.rrt_checks;
  j["sim_time_s"] = st.sim_time_s;
  j["frame_ms"] = frame_ms;
  j["frames_while_planning"] = frames_while_planning;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << j.dump(1) << "\n";
    if (!f) throw std::invalid_argument("status: cannot write '" + path + "'");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::invalid_argument("status: cannot write '" + path + "': " + ec.message());
}

}  // namespace app
