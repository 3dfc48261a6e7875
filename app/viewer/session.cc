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

#include "app/viewer/internal/session_outputs.h"
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
  if (scenario_) return world_->objects;
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
    world_ = planning::MakeScenarioState(*scenario_);
    aico_ = scenario_->aico;
    robot_scene_.reset();
    joint_q_ = scenario_->initial.problem.q0;
    status_ = "loaded scenario " + scenario_->name;
  } else {
    robot_scene_ = planning::LoadRobotScene(path, settings.robot_input);
    scenario_.reset();
    world_.reset();
    joint_q_ = robot_scene_->q;
    status_ = "loaded " + path;
  }
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
        settings->planner.max_iterations = aico_.max_iterations;
        settings->planner.tolerance = aico_.tolerance;
        settings->planner.damping = aico_.damping;
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
      if (!planning::IsAico(planning::ParsePlanner(settings->planner.planner))) {
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
      if (scenario_) joint_q_ = scenario_->initial.problem.q0;
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
  if (scenario_) return planning::tau(scenario_->initial.problem);
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
  planning::ReportWritheTotal(*scenario_, *world_, q, &w);
  return w;
}

}  // namespace app
