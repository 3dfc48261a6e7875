// app::Session: the state behind the interactive window and its headless twin — the loaded
// scenario or robot scene, the latest plan with every AICO sweep, and the commands that change
// them. UI buttons and `--script` lines both become SessionCommands; nothing else mutates a
// Session. Plans, re-plans and ODE simulations run on a worker thread (app/viewer/worker.h): the draw
// thread applies commands, calls Poll() once per frame to take over finished sweeps, results and
// simulation frames, and never waits for a solve (only kPlan and Wait() do, for scripts/tests).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "planning/motion/robot_scene.h"
#include "app/viewer/settings.h"
#include "app/viewer/worker.h"
#include "planning/robot/kinematics.h"
#include "planning/physics/grasp_simulation.h"
#include "planning/physics/stability.h"
#include "planning/motion/planner.h"
#include "planning/motion/replan.h"
#include "planning/motion/scenario.h"

namespace app {

// One action. `text` and `value` carry the argument where the kind needs one.
struct SessionCommand {
  enum class Kind {
    kLoad,       // text = scenario / URDF / scene JSON path
    kPlan,       // run settings.planner on the scenario and wait; shows the final trajectory
    kPlanAsync,  // start settings.planner on the worker and return; sweeps appear as they come
    kStep,       // value = N: run N more real AICO sweeps on the worker (starts a stepped solve if
                 // none is parked), then hold the solver; shows the latest sweep
    kRrtStep,    // value = N: grow the RRT/BiRRT trees of settings.planner by N iterations
    kCancel,     // stop the worker's job at its next sweep/step; its partial output is dropped
    kPlay,       // start playback of the shown trajectory
    kPause,      // stop playback
    kSeek,       // value = time to show [s] from the trajectory's start (rounded to a slice)
    kSetJoint,   // value = angle [rad] of joint index `index` (clears the trajectory)
    kReset,      // back to the start configuration, no trajectory
    kGraspRun,   // transfer settings.grasp to the SDH and run the ODE stability test on the
                 // worker, recording it
    kGraspStep,  // value = recorded simulation frames to advance (negative: back)
    kSimStep,    // value = N: advance the live ODE test by N physics steps (starts one if none is
                 // parked), then hold it
    kSimPhase,   // value = N: advance the live ODE test to the end of the N-th protocol phase from
                 // here (closing, gravity +x, ...; StabilityRun::StepPhase), then hold it
    kMove,       // text = object, position = new world position [m] of its frame: moves the object
                 // and the tasks attached to it (planning/motion/replan.h) and, while an AICO plan is
                 // shown, re-plans on the worker with planning::ReplanFrom from the shown slice
                 // (receding horizon: that plan shifted as the start; playback goes on); without
                 // one it plans from the start in the moved scene
  };
  SessionCommand() = default;
  explicit SessionCommand(Kind k, std::string t = "", int i = 0, double v = 0.0)
      : kind(k), text(std::move(t)), index(i), value(v) {}

  Kind kind = Kind::kReset;
  std::string text;
  int index = 0;
  double value = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
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
  bool finished = false;       // false while the live simulation runs or is held between steps
};

// One RRT/BiRRT tree as drawn: the grasp point (sdh_grasp_link, else the robot's last link) of
// every node's configuration [m, world frame] and the node's parent (−1: the root).
struct RrtTreeView {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> parents;
};

// What the worker is doing, for the progress display and `status FILE`.
struct WorkerStatus {
  std::string job;                      // "plan", "step", "grasp", "move" or "" when idle
  bool computing = false;               // a job runs now (not held between steps)
  bool held = false;                    // a stepped job waits for the next step
  int sweep = 0;                        // AICO sweeps done so far (latest plan)
  int max_sweeps = 0;                   // their limit (settings.planner.max_iterations)
  double cost = 0.0;                    // cost of the latest sweep
  long rrt_nodes = 0;                   // nodes of the RRT trees (0 when none is shown)
  long rrt_checks = 0, rrt_budget = 0;  // collision checks used / allowed
  double sim_time_s = 0.0;              // simulated time of the latest ODE frame
};

class Session {
 public:
  Session() = default;
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  // Cancels and joins the worker's job.
  ~Session();

  // Applies one command; may update `settings` (shown sweep, frame, playback). Throws
  // std::invalid_argument for bad arguments (unknown file, joint index out of range, unknown
  // object). Commands that replace the scenario or the plan cancel the worker's job first (its
  // output is dropped) without waiting for it.
  void Apply(const SessionCommand& command, Settings* settings);
  // Takes over what the worker produced since the last call (sweeps, the result, simulation
  // frames) and starts queued jobs; call once per frame. Never blocks on a running job.
  void Poll(Settings* settings);
  // Blocks until the worker is idle or holds a stepped job, then Poll()s (scripts and tests).
  void Wait(Settings* settings);
  WorkerStatus worker_status(const Settings& settings) const;
  // True while a job runs or is held between steps.
  bool busy() const { return worker_.busy(); }
  // True when nothing runs: the worker is idle (and its output taken over) or holds a stepped
  // job. Scripts' plan/step/wait/grasp lines keep drawing frames until this holds.
  bool settled() const;

  // Advances playback by settings->play_stride slices when playing (stops at the end).
  void Tick(Settings* settings) const;

  bool loaded() const { return scenario_ != nullptr || robot_scene_.has_value(); }
  bool has_scenario() const { return scenario_ != nullptr; }
  const planning::Scenario* scenario() const { return scenario_.get(); }
  // The world shown and planned in (objects where `move` put them); null without a scenario.
  const planning::ScenarioState* world() const { return world_.get(); }
  // The solver options the next plan uses (the planner panel's; the scenario's on load).
  const planning::AicoOptions& aico_options() const { return aico_; }
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
  // Time step [s] between the shown trajectory's slices (τ of the scenario; 1 without one).
  double ShownDt(const Settings& settings) const;
  // max |W_ij| over every slice of the shown trajectory (or the shown q without one): one fixed,
  // symmetric colour range [−limit, limit] for the heatmap while it plays. Cached per plan/sweep.
  double HeatmapLimit(const Settings& settings) const;

  const std::vector<SweepRecord>& sweeps() const { return sweeps_; }
  const std::optional<planning::PlanResult>& result() const { return result_; }
  const Eigen::VectorXd& joint_q() const { return joint_q_; }
  const std::optional<GraspReplay>& grasp() const { return grasp_; }
  // The trees of the latest RRT/BiRRT plan as they grow (tree 0 from the start, 1 from the goal).
  const std::vector<RrtTreeView>& rrt_trees() const { return rrt_trees_; }
  // World-frame gravity [m/s²] during recorded grasp frame `frame` (zero while closing).
  Eigen::Vector3d GraspGravity(int frame) const;
  // One line describing the last action, for the status bar and logs.
  const std::string& status() const { return status_; }
  void set_status(const std::string& status) { status_ = status; }

 private:
  struct PlanOutput;
  struct GraspOutput;
  void Load(const std::string& path, const Settings& settings);
  // Starts settings.planner on the worker (budget < 0: to the end; else that many AICO sweeps).
  void StartPlan(Settings* settings, long budget);
  // The live ODE stability test of settings.grasp (budget < 0: to the end; else that many
  // units, whole protocol phases when `phases`, else physics steps).
  void StartGrasp(Settings* settings, long budget, bool phases = false);
  // The RRT/BiRRT of settings.planner as a resumable solver (planning::RrtSolver), one
  // iteration per worker checkpoint, publishing its trees.
  void StartRrt(Settings* settings, long budget);
  void StartMove(const SessionCommand& command, Settings* settings);
  // The output of a new plan job (shown from now on) and the job's name ("plan", or
  // `stepped_name` when budget >= 0) and budget.
  std::shared_ptr<PlanOutput> NewPlanJob(long budget, const char* stepped_name, Worker::Job* job);
  // Cancels the worker's job and forgets its output (the job ends at its next checkpoint).
  void DropJob();
  void ShowPlanResult(Settings* settings);

  std::shared_ptr<const planning::Scenario> scenario_;  // the model, never changed
  // The world the viewer shows and plans in: objects where `move` put them (shared with the job
  // that reads it; moved only when no job runs).
  std::shared_ptr<planning::ScenarioState> world_;
  // The solver options of the planner panel (from the scenario's on load).
  planning::AicoOptions aico_;
  std::optional<planning::RobotScene> robot_scene_;
  Eigen::VectorXd joint_q_;  // slider configuration
  std::optional<planning::PlanResult> result_;
  // The receding-horizon plan behind result_ after a `move` (its velocities and the scenario
  // slice of its first column); empty for a plan from the start.
  std::optional<planning::RecedingPlan> horizon_;
  std::vector<SweepRecord> sweeps_;
  std::optional<GraspReplay> grasp_;
  std::vector<RrtTreeView> rrt_trees_;
  long rrt_checks_ = 0;
  std::string status_;
  long plan_version_ = 0;  // bumped whenever sweeps_ or result_ change
  mutable std::pair<long, int> heatmap_key_{-1, 0};
  mutable double heatmap_limit_ = 0.0;
  std::shared_ptr<PlanOutput> plan_out_;    // output of the plan job being shown, if any
  std::shared_ptr<GraspOutput> grasp_out_;  // output of the live simulation, if any
  // Last: destroyed (cancelled and joined) before the state its job writes to. Its jobs run at
  // nice +kWorkerNice so that frames keep coming while it plans on a busy machine.
  static constexpr int kWorkerNice = 3;
  Worker worker_{kWorkerNice};
};

// What the viewer's draw loop measured, for `status FILE`.
struct FrameStats {
  // Wall time [ms] of each recent drawn frame (from its start to the next frame's start: the
  // whole draw loop iteration) and whether the worker planned during it.
  std::vector<double> frame_ms;
  std::vector<bool> frame_planning;
  long frames = 0;                 // frames drawn so far
  long frames_while_planning = 0;  // of which while the worker planned
  long scene_renders = 0;          // 3-D scene renders so far (the other frames reused the image)
};

// Writes `status` and `frames` as the JSON object {"planner", "planning", "held", "job",
// "sweep", "max_sweeps", "cost", "rrt_nodes", "rrt_checks", "sim_time_s", "frame_ms": [...],
// "frame_planning": [...], "frames", "frames_while_planning", "scene_renders"} to `path`, through
// a temporary file renamed into place (never a half-written file). Throws std::invalid_argument
// when it cannot be written.
void WriteStatusJson(const std::string& path, const std::string& planner,
                     const WorkerStatus& status, const FrameStats& frames);

// Parses a `--script` file: one command per line, `#` comments. Lines (ScriptUsage() lists
// them):
//   load PATH | plan [async] | step [N] | wait | cancel | rrt_step N | sim_step N | sim_phase [N] |
//   move OBJECT X Y Z | status FILE | play | pause | seek SECONDS | joint INDEX ANGLE | reset |
//   toggle chains|collision|grid|contacts|heatmap|cost | planner aico|rrt|birrt | seed N |
//   damping LAMBDA (AICO's initial damping; loading a scenario resets it to aico.damping) |
//   camera YAW PITCH DISTANCE [TX TY TZ] | frames N (draw N frames) | screenshot PATH |
//   click WIDGET (press a named widget, e.g. "Plan", "chains") | grasp NAME METHOD |
//   grasp_step N | quit
// Session commands come back as Commands; view-only lines are applied to `settings` at the
// right moment by RunScript (viewer). Throws std::invalid_argument "FILE:LINE: ..." for unknown
// verbs, wrong argument counts and bad values, listing the valid choices as "(valid: a, b, c)";
// also for numbers out of range: frames N in [1, kMaxScriptFrames] (all frames lines together <=
// kMaxScriptTotalFrames), step/rrt_step/sim_step N in [1, 1e6], sim_phase N in [1, 7] (the
// protocol's phases), seed in [0, 2^32 − 1], finite numbers elsewhere; files larger than
// topology::kMaxInputFileBytes are refused.
inline constexpr int kMaxScriptFrames = 100000;
inline constexpr long long kMaxScriptTotalFrames = 1000000;
struct ScriptLine {
  std::string file;
  int line = 0;
  std::string verb;
  std::vector<std::string> args;
};
std::vector<ScriptLine> ParseScript(const std::string& path);
// "(valid: a, b, c)": the one format in which script and UI errors list the valid choices.
std::string ValidChoices(const std::vector<std::string>& choices);
// The toggles `toggle NAME` accepts.
const std::vector<std::string>& ScriptToggles();

}  // namespace app
