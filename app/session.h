// app::Session: the state behind the interactive window and its headless twin — the loaded
// scenario or robot scene, the latest plan with every AICO sweep, and the commands that change
// them. UI buttons and `--script` lines both become SessionCommands; nothing else mutates a
// Session.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/robot_scene.h"
#include "app/settings.h"
#include "planning/kinematics.h"
#include "planning/physics/grasp_simulation.h"
#include "planning/physics/stability.h"
#include "planning/planner.h"
#include "planning/scenario.h"

namespace app {

// One action. `text` and `value` carry the argument where the kind needs one.
struct SessionCommand {
  enum class Kind {
    kLoad,       // text = scenario / URDF / scene JSON path
    kPlan,       // run settings.planner on the scenario; shows the final trajectory
    kStep,       // show the next AICO sweep (plans first, recording every sweep, if needed)
    kPlay,       // start playback of the shown trajectory
    kPause,      // stop playback
    kSeek,       // value = time slice to show
    kSetJoint,   // value = angle [rad] of joint index `index` (clears the trajectory)
    kReset,      // back to the start configuration, no trajectory
    kGraspRun,   // transfer settings.grasp to the SDH and run the ODE stability test, recording it
    kGraspStep,  // value = recorded simulation frames to advance (negative: back)
  };
  SessionCommand() = default;
  explicit SessionCommand(Kind k, std::string t = "", int i = 0, double v = 0.0)
      : kind(k), text(std::move(t)), index(i), value(v) {}

  Kind kind = Kind::kReset;
  std::string text;
  int index = 0;
  double value = 0.0;
};

// One AICO sweep as recorded through the solver's callback.
struct SweepRecord {
  int sweep = 0;
  double cost = 0.0;
  bool accepted = false;
  Eigen::MatrixXd q;  // trajectory after the sweep (n × (T+1))
};

// A recorded ODE stability test of one transferred grasp: the simulation description and its state
// every `stride` steps (closing phase 0, then gravity directions 1..6).
struct GraspReplay {
  std::string grasp, method;
  planning::physics::SimHand hand;
  planning::physics::SimObject object;
  struct Frame {
    int phase = 0;
    planning::physics::SimState state;
  };
  std::vector<Frame> frames;
  int stride = 20;  // steps between recorded frames (20 ms at 1 kHz)
  planning::physics::StabilityResult result;
  double winding_error = 0.0;  // |robot winding − target| of the transfer
};

class Session {
 public:
  Session() = default;

  // Applies one command; may update `settings` (shown sweep, frame, playback). Throws
  // std::invalid_argument for bad arguments (unknown file, joint index out of range).
  void Apply(const SessionCommand& command, Settings* settings);

  // Advances playback by settings->play_stride slices when playing (stops at the end).
  void Tick(Settings* settings) const;

  bool loaded() const { return scenario_ != nullptr || robot_scene_.has_value(); }
  bool has_scenario() const { return scenario_ != nullptr; }
  const planning::Scenario* scenario() const { return scenario_.get(); }
  const planning::Robot& robot() const;
  const planning::Environment& objects() const;
  std::vector<std::string> joint_names() const;

  // Configuration shown for `settings`: slice settings.frame of the shown trajectory, else the
  // joint sliders' configuration.
  Eigen::VectorXd ShownQ(const Settings& settings) const;
  // Number of slices of the shown trajectory (0 when there is none).
  int num_frames(const Settings& settings) const;
  // Writhe matrix of the scenario's report pair at q (empty when the scenario has none).
  Eigen::MatrixXd WritheAt(const Eigen::VectorXd& q) const;

  const std::vector<SweepRecord>& sweeps() const { return sweeps_; }
  const std::optional<planning::PlanResult>& result() const { return result_; }
  const Eigen::VectorXd& joint_q() const { return joint_q_; }
  const std::optional<GraspReplay>& grasp() const { return grasp_; }
  // World-frame gravity [m/s²] during recorded grasp frame `frame` (zero while closing).
  Eigen::Vector3d GraspGravity(int frame) const;
  // One line describing the last action, for the status bar and logs.
  const std::string& status() const { return status_; }
  void set_status(const std::string& status) { status_ = status; }

 private:
  void Load(const std::string& path, const Settings& settings);
  void Plan(Settings* settings, bool record_sweeps);
  void RunGrasp(Settings* settings);

  std::unique_ptr<planning::Scenario> scenario_;
  std::optional<RobotScene> robot_scene_;
  Eigen::VectorXd joint_q_;  // slider configuration
  std::optional<planning::PlanResult> result_;
  std::vector<SweepRecord> sweeps_;
  std::optional<GraspReplay> grasp_;
  std::string status_;
};

// Parses a `--script` file: one command per line, `#` comments. Lines:
//   load PATH | plan | step | play | pause | seek SLICE | joint INDEX ANGLE | reset |
//   toggle chains|collision|grid|contacts|heatmap|cost | planner aico|rrt|birrt | seed N |
//   camera YAW PITCH DISTANCE | frames N (render N frames) | screenshot PATH |
//   click WIDGET (press a named widget, e.g. "Plan", "chains") | quit
// Session commands come back as Commands; view-only lines are applied to `settings` at the
// right moment by RunScript (viewer). Throws std::invalid_argument naming file and line, also for
// numbers out of range: frames N in [1, kMaxScriptFrames] (all frames lines together <=
// kMaxScriptTotalFrames), seed in [0, 2^32 − 1], finite numbers elsewhere; files larger than
// topology::kMaxInputFileBytes are refused.
inline constexpr int kMaxScriptFrames = 100000;
inline constexpr long long kMaxScriptTotalFrames = 1000000;
struct ScriptLine {
  int line = 0;
  std::string verb;
  std::vector<std::string> args;
};
std::vector<ScriptLine> ParseScript(const std::string& path);

}  // namespace app
