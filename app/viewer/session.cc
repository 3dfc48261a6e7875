#include "app/viewer/session.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "base/assets.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/hand_builder.h"
#include "planning/physics/ode_runtime.h"
#include "planning/motion/replan.h"
#include "base/file_read.h"
#include "base/numbers.h"

namespace app {
namespace {

// A JSON file with a "tasks" array is a planning scenario; anything else LoadRobotScene takes.
// Read bounded like every reader: a file that cannot be read (missing, larger than
// topology::kMaxInputFileBytes, `/dev/zero`) is not a scenario, and the robot-scene loader then
// names the problem.
bool IsPlanningScenario(const std::string& path) {
  if (path.size() < 5 || path.substr(path.size() - 5) != ".json") return false;
  std::string text;
  try {
    text = base::ReadFileBounded(path, "scenario");
  } catch (const std::invalid_argument&) {
    return false;
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
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
  const std::string path = base::ResolveScenarioPath(arg);
  result_.reset();
  horizon_.reset();
  sweeps_.clear();
  rrt_trees_.clear();
  ++plan_version_;
  if (IsPlanningScenario(path)) {
    planning::ScenarioOverrides overrides;
    if (settings.planner.start_wrap_deg >= 0) {
      overrides.start_wrap_deg = settings.planner.start_wrap_deg;
    }
    overrides.package_paths = planning::PackagePaths(settings.robot_input.package_paths);
    overrides.srdf = settings.robot_input.srdf;
    scenario_ = planning::LoadScenarioArg(path, overrides);
    robot_scene_.reset();
    joint_q_ = scenario_->problem.q0;
    status_ = "loaded scenario " + scenario_->name;
  } else {
    robot_scene_ = planning::LoadRobotScene(path, settings.robot_input);
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
  std::optional<planning::RecedingPlan> horizon;  // re-plan after a move: the new plan
  int frame_at_start = -1;                        // re-plan: the frame shown when it started
  std::vector<RrtTreeView> trees;                 // RRT plans: the trees so far
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
  // What the budgeted units of a stepped run are, in the order asked: {count, whole phases}
  // (a phase unit is StabilityRun::StepPhase, else one physics step); empty: physics steps.
  std::deque<std::pair<long, bool>> units;
  std::string error;
};

namespace {

// Whether the next budgeted unit of a live simulation is a whole phase (takes it from
// out->units; a run without units steps physics).
template <typename Output>
bool NextUnitIsPhase(Output* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  if (out->units.empty()) return false;
  const bool phases = out->units.front().second;
  if (--out->units.front().first <= 0) out->units.pop_front();
  return phases;
}

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
  horizon_.reset();
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
      // AICO: one real sweep per worker checkpoint (step N runs N, then holds the solver).
      planning::PlanResult r =
          planner == planning::Planner::kAico
              ? planning::RunPlanner(
                    *scenario, planner, seed,
                    [&](int sweep, double cost, bool accepted, const planning::Trajectory& q) {
                      {
                        std::lock_guard<std::mutex> lock(out->mutex);
                        out->sweeps.push_back({sweep, cost, accepted, q.q});
                      }
                      worker.Checkpoint();
                    })
              : planning::RunPlanner(*scenario, planner, seed);
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
      // The RRT set-up of RunPlanner (planning/motion/planner.h).
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
  const std::vector<std::string> names = planning::ObjectNames(*scenario_);
  if (std::find(names.begin(), names.end(), c.text) == names.end()) {
    throw std::invalid_argument("move: no object '" + c.text + "' " + ValidChoices(names));
  }
  if (!c.position.allFinite()) throw std::invalid_argument("move: position is not finite");
  // The plan the arm executes: the shown AICO trajectory (T+1 slices) from scenario slice
  // horizon_->start_slice (0 for a plan from the start), `elapsed` slices of it done.
  const int T = scenario_->problem.num_steps;
  std::optional<planning::RecedingPlan> plan;
  const int elapsed = std::clamp(settings->frame, 0, T);
  if (num_frames(*settings) == T + 1 &&
      planning::ParsePlanner(settings->planner.planner) == planning::Planner::kAico) {
    const bool shows_result =
        settings->sweep < 0 || settings->sweep >= static_cast<int>(sweeps_.size());
    const planning::Trajectory shown{
        shows_result ? result_->trajectory.q : sweeps_[settings->sweep].q, ShownDt(*settings)};
    plan = horizon_ && shows_result
               ? *horizon_
               : planning::MakeRecedingPlan(shown, {}, horizon_ ? horizon_->start_slice : 0);
  }
  // No job may read the scenario while it moves (a running one stops at its next sweep).
  DropJob();
  worker_.Wait(/*join_parked=*/true);
  const std::vector<int> attached = planning::AttachedTasks(*scenario_, c.text);
  planning::MoveObjectWithTargets(scenario_.get(), c.text, c.position, attached);
  if (!plan) {  // nothing executing: plan from the start in the moved scene
    StartPlan(settings, -1);
    status_ = "moved " + c.text + ": planning ...";
    return;
  }
  sweeps_.clear();
  ++plan_version_;
  auto out = std::make_shared<PlanOutput>();
  out->what = "re-plan after moving " + c.text;
  out->follow = false;  // the arm keeps executing the shown plan until the new one is there
  out->frame_at_start = settings->frame;
  plan_out_ = out;
  planning::ReplanOptions options;
  options.sweeps = settings->planner.max_iterations;
  std::shared_ptr<const planning::Scenario> scenario = scenario_;
  Worker::Job job;
  job.name = "move";
  job.run = [out, scenario, options, elapsed, plan = *plan](Worker& worker) mutable {
    RunRecordingEnd(out.get(), [&] {
      options.on_sweep = [&](int sweep, double cost, bool accepted, const planning::Trajectory& t) {
        {
          std::lock_guard<std::mutex> lock(out->mutex);
          out->sweeps.push_back({sweep, cost, accepted, t.q});
        }
        worker.Checkpoint();
      };
      // The library's receding-horizon step (planning/motion/replan.h), as RunReplanning runs it.
      planning::ReplanWorkspace ws(*scenario);
      planning::AicoResult a;
      planning::ReplanFrom(*scenario, elapsed, options, &ws, &plan, &a);
      planning::PlanResult r;
      r.report.planner = "aico (warm start)";
      planning::AddAicoAttempt(*scenario, a, &r);
      planning::NameFailure(&r.report);
      r.report.start_writhe_total = planning::ReportWritheTotal(*scenario, a.trajectory.q.col(0));
      std::lock_guard<std::mutex> lock(out->mutex);
      out->result = std::move(r);
      out->horizon = std::move(plan);
    });
  };
  worker_.Submit(std::move(job));
  status_ = "moved " + c.text + ": re-planning from slice " +
            std::to_string(plan->start_slice + elapsed) + " ...";
}

void Session::StartGrasp(Settings* settings, long budget, bool phases) {
  namespace phys = planning::physics;
  const std::string name = settings->grasp.grasp;
  const planning::TransferMethod method = planning::ParseTransferMethod(settings->grasp.method);
  auto in =
      std::make_shared<const planning::GraspInputs>(planning::LoadGraspInputs({base::AssetPath("grasps/" + name + ".json")}));
  DropJob();
  auto out = std::make_shared<GraspOutput>();
  out->replay.grasp = name;
  out->replay.method = settings->grasp.method;
  out->stepped = budget >= 0;
  if (budget >= 0) out->units.emplace_back(budget, phases);
  grasp_out_ = out;
  grasp_.reset();
  Worker::Job job;
  job.name = "grasp";
  job.budget = budget;
  job.run = [out, in, method](Worker& worker) {
    RunRecordingEnd(out.get(), [&] {
      // The trial's set-up (what RunGraspTrials prepares): transfer, ODE hand and object.
      const planning::HumanGrasp& grasp = in->grasps.at(0);
      const planning::TransferSetup setup = planning::MakeTransferSetup(
          in->human, in->lwr_sdh, planning::FindGraspObject(in->objects, grasp.object), grasp);
      const planning::TransferResult transfer = planning::TransferGrasp(setup, method);
      {
        std::lock_guard<std::mutex> lock(out->mutex);
        out->replay.hand = phys::BuildSimHand(setup.sdh, transfer.q, "sdh_palm");
        out->replay.object = phys::BuildSimObject(setup.object, setup.grasp.world_from_object);
        out->started = true;
      }
      // The stability test as a resumable run: one physics step or one whole phase per worker
      // checkpoint. Every stride-th step is recorded (also inside a phase), and the state a
      // stepped run holds at; a phase is cancelled between its steps.
      const phys::OdeRuntime ode;
      const int stride = out->replay.stride;
      long steps = 0;
      bool recorded = false;  // the latest step is recorded
      phys::StabilityRun run(ode, out->replay.hand, out->replay.object, phys::StabilityOptions{},
                             [&](int phase, const phys::GraspSimulation& sim) {
                               recorded = steps++ % stride == 0;
                               if (recorded) {
                                 std::lock_guard<std::mutex> lock(out->mutex);
                                 out->replay.frames.push_back({phase, sim.state()});
                               }
                               worker.ThrowIfCancelled();
                             });
      for (;;) {
        const long before = steps;
        if (NextUnitIsPhase(out.get())) {
          run.StepPhase();
        } else {
          run.StepPhysics();
        }
        if (steps == before) break;  // done
        if (worker.AtBudget() && !recorded) {
          std::lock_guard<std::mutex> lock(out->mutex);
          out->replay.frames.push_back({run.phase(), run.state()});
        }
        worker.Checkpoint();
      }
      std::lock_guard<std::mutex> lock(out->mutex);
      out->replay.result = run.result();
      out->replay.winding_error = (transfer.robot_winding - transfer.target_winding).norm();
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
      std::optional<planning::RecedingPlan> horizon = std::move(out->horizon);
      const std::string error = out->error, what = out->what;
      const int frame_at_start = out->frame_at_start;
      lock.unlock();
      if (result) {
        const int frame = settings->frame;
        result_ = std::move(result);
        horizon_ = std::move(horizon);
        ++plan_version_;
        ShowPlanResult(settings);
        if (frame_at_start >= 0) {  // a re-plan: go on from where execution is now
          settings->frame =
              std::clamp(frame - frame_at_start, 0, std::max(0, num_frames(*settings) - 1));
        }
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
    case K::kSimStep:
    case K::kSimPhase: {
      const bool phases = c.kind == K::kSimPhase;
      const long n = count(phases ? "sim_phase" : "sim_step");
      if (grasp_out_) {  // before the budget: the job reads what its next unit is
        std::lock_guard<std::mutex> lock(grasp_out_->mutex);
        grasp_out_->units.emplace_back(n, phases);
      }
      if (!grasp_out_ || !worker_.AddBudget(n)) StartGrasp(settings, n, phases);
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
      if (scenario_) {  // the planner panel starts from the scenario's own solver options
        settings->planner.max_iterations = scenario_->aico.max_iterations;
        settings->planner.tolerance = scenario_->aico.tolerance;
        settings->planner.damping = scenario_->aico.damping;
      }
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
      horizon_.reset();
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
      horizon_.reset();
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
      {"sim_phase", 0, 1, "sim_phase [N]"},
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
      {"damping", 1, 1, "damping LAMBDA"},
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
// kMaxScriptTotalFrames), "seed" an integer in [0, 2^32 − 1], "damping" a number in [0, 1e6],
// step/rrt_step/sim_step N in [1, 1e6], sim_phase N in [1, 7], "joint" an index in [0, 1e6] and a
// finite value, camera/seek/grasp_step/move finite numbers that fit a float; names from their fixed
// lists.
void CheckScriptArgs(const std::string& path, const ScriptLine& l, long long* total_frames) {
  const std::string at = path + ":" + std::to_string(l.line) + ": ";
  const auto where = [&](size_t i) { return at + "'" + l.args[i] + "'"; };
  const auto number = [&](size_t i, double lo, double hi) {
    const std::optional<double> v = base::ParseFiniteDouble(l.args[i]);
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
  } else if (l.verb == "damping") {
    number(0, 0.0, 1e6);
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
  } else if (l.verb == "sim_phase") {
    if (!l.args.empty()) integer(0, 1, planning::physics::StabilityRun::kNumPhases);
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
  std::istringstream in(base::ReadFileBounded(path, "script"));
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
                     const FrameStats& frames) {
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
  j["frame_ms"] = frames.frame_ms;
  j["frame_planning"] = frames.frame_planning;
  j["frames"] = frames.frames;
  j["frames_while_planning"] = frames.frames_while_planning;
  j["scene_renders"] = frames.scene_renders;
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
