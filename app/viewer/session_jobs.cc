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

#include "app/viewer/internal/session_outputs.h"
#include "app/viewer/session.h"
#include "base/assets.h"
#include "base/file_read.h"
#include "base/numbers.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/motion/replan.h"
#include "planning/physics/hand_builder.h"
#include "planning/physics/ode_runtime.h"
namespace app {

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
  planning::AicoOptions& a = aico_;
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
  std::shared_ptr<const planning::ScenarioState> world = world_;
  planning::PlanRequest request;
  request.planner = planner;
  request.seed = settings->planner.seed;
  request.aico = aico_;
  job.run = [out, scenario, world, request](Worker& worker) mutable {
    RunRecordingEnd(out.get(), [&] {
      // AICO: one real sweep per worker checkpoint (step N runs N, then holds the solver).
      request.state = world.get();
      if (planning::IsAico(request.planner)) {
        request.callback = [&](int sweep, double cost, bool accepted,
                               const planning::Trajectory& q) {
          {
            std::lock_guard<std::mutex> lock(out->mutex);
            out->sweeps.push_back({sweep, cost, accepted, q.q});
          }
          worker.Checkpoint();
        };
      }
      planning::PlanResult r = planning::RunPlanner(*scenario, request);
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
  std::shared_ptr<const planning::ScenarioState> world = world_;
  const unsigned seed = settings->planner.seed;
  job.run = [out, scenario, world, planner, seed](Worker& worker) {
    RunRecordingEnd(out.get(), [&] {
      const planning::Scenario& s = *scenario;
      // The RRT set-up of RunPlanner (planning/motion/planner.h).
      planning::CollisionData coll(s.robot, world->env, s.collision);
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
      // Reported and judged as RunPlanner reports every sampling planner.
      planning::PlanResult r =
          planning::SamplingPlanResult(s, *world, planner, solver.result(), coll);
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
  const int T = scenario_->initial.problem.num_steps;
  std::optional<planning::RecedingPlan> plan;
  const int elapsed = std::clamp(settings->frame, 0, T);
  if (num_frames(*settings) == T + 1 &&
      planning::IsAico(planning::ParsePlanner(settings->planner.planner))) {
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
  const std::vector<int> attached = planning::AttachedTasks(*scenario_, *world_, c.text);
  planning::MoveObjectWithTargets(*scenario_, world_.get(), c.text, c.position, attached);
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
  std::shared_ptr<const planning::ScenarioState> world = world_;
  Worker::Job job;
  job.name = "move";
  job.run = [out, scenario, world, options, elapsed, plan = *plan](Worker& worker) mutable {
    RunRecordingEnd(out.get(), [&] {
      options.on_sweep = [&](int sweep, double cost, bool accepted, const planning::Trajectory& t) {
        {
          std::lock_guard<std::mutex> lock(out->mutex);
          out->sweeps.push_back({sweep, cost, accepted, t.q});
        }
        worker.Checkpoint();
      };
      // The library's receding-horizon step (planning/motion/replan.h), as RunReplanning runs it.
      planning::ReplanWorkspace ws(*scenario, *world);
      planning::AicoResult a;
      planning::ReplanFrom(*scenario, *world, elapsed, options, &ws, &plan, &a);
      planning::PlanResult r;
      r.report.planner = "aico (warm start)";
      planning::AddAicoAttempt(*scenario, *world, a, &r);
      planning::NameFailure(&r.report);
      r.report.start_writhe_total =
          planning::ReportWritheTotal(*scenario, *world, a.trajectory.q.col(0));
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
  auto in = std::make_shared<const planning::GraspInputs>(
      planning::LoadGraspInputs({base::AssetPath("grasps/" + name + ".json")}));
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

}  // namespace app
