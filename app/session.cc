#include "app/session.h"

#include <algorithm>
#include <cmath>
#include <fstream>
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

void Session::Plan(Settings* settings, bool record_sweeps) {
  if (!scenario_) throw std::invalid_argument("plan: the loaded file is not a planning scenario");
  // The solver options come from the settings (what the planner panel edits).
  planning::Scenario& s = *scenario_;
  s.aico.max_iterations = settings->planner.max_iterations;
  s.aico.tolerance = settings->planner.tolerance;
  s.aico.damping = settings->planner.damping;
  const planning::Planner planner = planning::ParsePlanner(settings->planner.planner);
  sweeps_.clear();
  planning::AicoCallback record;
  if (record_sweeps || planner == planning::Planner::kAico) {
    record = [this](int sweep, double cost, bool accepted, const planning::Trajectory& t) {
      sweeps_.push_back({sweep, cost, accepted, t.q});
    };
  }
  result_ = planning::RunPlanner(s, planner, settings->planner.seed, record);
  const planning::PlanReport& r = result_->report;
  std::ostringstream msg;
  msg << r.planner << ": " << (r.success ? "success" : "FAILED") << ", " << r.collision_checks
      << " collision checks, " << r.iterations << " iterations, writhe " << r.start_writhe_total
      << " -> " << r.final_writhe_total;
  status_ = msg.str();
  settings->sweep = -1;
  settings->frame = 0;
}

void Session::RunGrasp(Settings* settings) {
  namespace phys = planning::physics;
  const std::string name = settings->grasp.grasp;
  const planning::TransferMethod method = planning::ParseTransferMethod(settings->grasp.method);
  const GraspInputs in = LoadGraspInputs({AssetPath("grasps/" + name + ".json")});

  GraspReplay replay;
  replay.grasp = name;
  replay.method = settings->grasp.method;
  phys::GraspTrialHooks hooks;
  int step = 0;
  hooks.on_start = [&](const planning::TransferSetup&, const planning::TransferResult&,
                       const phys::SimHand&, const phys::SimObject&) -> phys::StepCallback {
    return [&](int phase, const phys::GraspSimulation& sim) {
      if (step++ % replay.stride == 0) replay.frames.push_back({phase, sim.state()});
    };
  };
  phys::OdeRuntime ode;
  phys::GraspTrialsResult trials =
      phys::RunGraspTrials(ode, in.human, in.lwr_sdh, in.objects, in.grasps, {method},
                           phys::StabilityOptions{}.sim.mu, hooks);
  phys::GraspTrial& trial = trials.trials.at(0).at(0);
  replay.hand = std::move(trial.hand);
  replay.object = std::move(trial.object);
  replay.result = std::move(trial.stability);
  replay.winding_error = trial.winding_error;
  std::ostringstream msg;
  msg << name << " (" << replay.method << "): " << replay.result.directions_passed
      << "/6 gravity directions held, "
      << (replay.result.stable ? "stable" : phys::ToString(replay.result.status)) << ", "
      << replay.frames.size() << " frames";
  status_ = msg.str();
  grasp_ = std::move(replay);
  settings->grasp.active = true;
  settings->grasp.frame = 0;
  settings->camera_initialised = false;
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
  switch (c.kind) {
    case K::kGraspRun:
      RunGrasp(settings);
      return;
    case K::kGraspStep: {
      if (!grasp_) RunGrasp(settings);
      const int n = static_cast<int>(grasp_->frames.size());
      settings->grasp.active = true;
      settings->grasp.frame =
          std::clamp(settings->grasp.frame + static_cast<int>(c.value), 0, std::max(0, n - 1));
      return;
    }
    case K::kLoad:
      Load(c.text, *settings);
      settings->scenario_path = c.text;
      settings->sweep = -1;
      settings->frame = 0;
      settings->playing = false;
      settings->camera_initialised = false;
      return;
    case K::kPlan:
      Plan(settings, /*record_sweeps=*/true);
      settings->playing = false;
      return;
    case K::kStep: {
      if (!result_) {
        Plan(settings, /*record_sweeps=*/true);
        settings->sweep = sweeps_.empty() ? -1 : 0;
      } else if (!sweeps_.empty()) {
        const int last = static_cast<int>(sweeps_.size()) - 1;
        settings->sweep = settings->sweep < 0 ? 0 : std::min(settings->sweep + 1, last);
      }
      if (settings->sweep >= 0) {
        const SweepRecord& s = sweeps_[settings->sweep];
        std::ostringstream msg;
        msg << "sweep " << s.sweep << " of " << sweeps_.size() << ": cost " << s.cost
            << (s.accepted ? " (accepted)" : " (rejected)");
        status_ = msg.str();
      }
      settings->frame = std::max(0, num_frames(*settings) - 1);
      return;
    }
    case K::kPlay:
      if (settings->frame >= num_frames(*settings) - 1) settings->frame = 0;
      settings->playing = num_frames(*settings) > 1;
      return;
    case K::kPause:
      settings->playing = false;
      return;
    case K::kSeek: {
      const int n = num_frames(*settings);
      settings->frame = n == 0 ? 0 : std::clamp(static_cast<int>(c.value), 0, n - 1);
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
      result_.reset();
      sweeps_.clear();
      settings->sweep = -1;
      settings->frame = 0;
      settings->playing = false;
      return;
    }
    case K::kReset:
      if (scenario_) joint_q_ = scenario_->problem.q0;
      if (robot_scene_) joint_q_ = robot_scene_->q;
      result_.reset();
      sweeps_.clear();
      settings->sweep = -1;
      settings->frame = 0;
      settings->playing = false;
      status_ = "reset";
      return;
  }
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

// The numeric arguments of a script line, checked when the script is read (the viewer converts
// them later): "frames" an integer in [1, kMaxScriptFrames] (and all frames lines together at
// most kMaxScriptTotalFrames), "seed" an integer in [0, 2^32 − 1], "joint" an index in [0, 1e6]
// and a finite value, camera/seek/grasp_step finite numbers that fit a float.
void CheckScriptNumbers(const std::string& path, const ScriptLine& l, long long* total_frames) {
  const auto where = [&](size_t i) {
    return path + ":" + std::to_string(l.line) + ": '" + l.args[i] + "'";
  };
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
  if (l.verb == "frames") {
    *total_frames += integer(0, 1, kMaxScriptFrames);
    if (*total_frames > kMaxScriptTotalFrames) {
      throw std::invalid_argument(path + ":" + std::to_string(l.line) + ": more than " +
                                  std::to_string(kMaxScriptTotalFrames) +
                                  " frames in the script (limit)");
    }
  } else if (l.verb == "seed") {
    integer(0, 0, 4294967295.0);
  } else if (l.verb == "joint") {
    integer(0, 0, 1e6);
    number(1, -1e6, 1e6);
  } else if (l.verb == "camera") {
    number(0, -1e6, 1e6);
    number(1, -1e6, 1e6);
    number(2, 1e-6, 1e6);
  } else if (l.verb == "seek" || l.verb == "grasp_step") {
    number(0, -1e9, 1e9);
  }
}

}  // namespace

std::vector<ScriptLine> ParseScript(const std::string& path) {
  std::istringstream in(topology::ReadFileBounded(path, "script"));
  static const std::vector<std::pair<std::string, int>> kVerbs = {
      {"load", 1}, {"plan", 0},   {"step", 0},      {"play", 0},       {"pause", 0},
      {"seek", 1}, {"joint", 2},  {"reset", 0},     {"toggle", 1},     {"planner", 1},
      {"seed", 1}, {"camera", 3}, {"frames", 1},    {"screenshot", 1}, {"click", 1},
      {"quit", 0}, {"grasp", 2},  {"grasp_step", 1}};
  std::vector<ScriptLine> lines;
  std::string raw;
  int n = 0;
  long long total_frames = 0;
  while (std::getline(in, raw)) {
    ++n;
    std::istringstream ss(raw);
    ScriptLine l;
    l.line = n;
    if (!(ss >> l.verb) || l.verb[0] == '#') continue;
    for (std::string a; ss >> a;) l.args.push_back(a);
    const auto it = std::find_if(kVerbs.begin(), kVerbs.end(),
                                 [&](const auto& v) { return v.first == l.verb; });
    if (it == kVerbs.end()) {
      throw std::invalid_argument(path + ":" + std::to_string(n) + ": unknown command '" + l.verb +
                                  "'");
    }
    if (static_cast<int>(l.args.size()) != it->second) {
      throw std::invalid_argument(path + ":" + std::to_string(n) + ": '" + l.verb + "' takes " +
                                  std::to_string(it->second) + " argument(s)");
    }
    CheckScriptNumbers(path, l, &total_frames);
    lines.push_back(std::move(l));
  }
  return lines;
}

}  // namespace app
