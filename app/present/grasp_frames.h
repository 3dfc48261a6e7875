// Frames of grasp-transfer trials, and the trial observers `grasp transfer` and the demo share.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/grasp_trials.h"
#include "render/frames.h"
#include "render/offscreen_context.h"
#include "render/renderer.h"
#include "visualize/scene_builder.h"

namespace app {

// Renders (480x360) the human grasp, the SDH approach (AICO slices) and the final SDH grasp, then
// the ODE closing and the six gravity trials. Constructing it opens a GL context (throws
// EnvironmentError when there is none).
class GraspFrameWriter {
 public:
  GraspFrameWriter();

  // DIR/transfer_*.png: the human grasp, then every slice of transfer.trajectory, each with the
  // grasp, method and time (or slice index) in a corner and as its contact-sheet label; and, when
  // the trajectory is not empty, DIR/side_by_side.png (968x360): the human grasp (left) and the
  // final SDH grasp (right), seen by one camera that frames both, so both halves have the same
  // scale.
  void Transfer(const std::string& dir, const planning::TransferSetup& setup,
                const planning::TransferResult& transfer);

  // Starts DIR/stability_*.png (+ contact sheet and video) and returns the callback for
  // TestGraspStability with `options`: a frame every 100 steps while closing (phase 0), every 250
  // steps of each gravity direction, and the last state of every phase (so a direction that ends
  // early still shows how it ended), gravity drawn as a line. Each frame carries its time and
  // gravity direction in a corner and as its contact-sheet label ("t = 0.40 s, g = −z"; t counts
  // from the start of closing, then from the moment gravity is switched on). `hand` and `object`
  // must outlive the test. Call FinishStability() with the test's result afterwards.
  planning::physics::StepCallback Stability(const std::string& dir,
                                            const planning::physics::SimHand& hand,
                                            const planning::physics::SimObject& object,
                                            const planning::physics::StabilityOptions& options);
  // The same for any engine that reports its state after every step (phase 0 closing, 1..6 the
  // gravity directions; e.g. planning::physics::TestGraspStabilityMujoco's StateCallback).
  std::function<void(int phase, const planning::physics::SimState& state)> StabilityStates(
      const std::string& dir, const planning::physics::SimHand& hand,
      const planning::physics::SimObject& object,
      const planning::physics::StabilityOptions& options);
  // Renders the last phase's end, labels the end of every phase with its outcome (closing: no
  // grasp / blew up; each direction: held, object dropped, slipped, rotated, lost contact, blew
  // up; these frames are always on the contact sheet) and writes the contact sheet and video.
  void FinishStability(const planning::physics::StabilityResult& result);

  // What the latest stability sequence was drawn with (tests): the protocol given to Stability(),
  // the state at the end of closing (the pose every gravity direction starts from), and how each
  // phase ended as its last frame's label says (FinishStability: 7 entries, closing first).
  const planning::physics::StabilityOptions& stability_options() const { return stability_; }
  const planning::physics::SimState& closure_state() const { return closure_state_; }
  const std::vector<std::string>& phase_outcomes() const { return phase_outcome_; }

  // With `on`, the stability videos are queued and encoded several at a time by one ffmpeg
  // (render::VideoBatch): the same files, written by FlushVideos() (or the destructor, or once
  // a few are queued) instead of by FinishStability(). Flush before the frames' folder moves.
  void set_batch_videos(bool on) { batch_videos_ = on; }
  void FlushVideos() { videos_.Flush(); }

 private:
  render::Image SideBySide(const render::Scene& left, const render::Scene& right,
                           const Eigen::Vector3f& view);
  // Whether the latest human-grasp frame was rendered from these inputs (the same pixels).
  bool SameHumanFrame(const planning::TransferSetup& setup) const;

  render::OffscreenContext context_;
  render::Renderer renderer_;
  visualize::SceneMeshCache cache_;
  render::Camera camera_;
  Eigen::Vector3f view_ = Eigen::Vector3f(1.0f, 1.3f, 0.8f);
  bool camera_set_ = false;
  // The latest human-grasp frame and what it was rendered from: the methods of one grasp share
  // it, so it is rendered once per grasp (and process).
  struct HumanFrame {
    std::string grasp, object, hand;
    Eigen::VectorXd q;
    Eigen::Matrix4d world_from_object, sdh_placement;
    render::Scene scene;
    render::Camera camera;
    Eigen::Vector3f view;
    render::Image image;
  };
  std::unique_ptr<HumanFrame> human_frame_;
  bool batch_videos_ = false;
  render::VideoBatch videos_;  // before writer_: outlives the writers that queue into it
  std::unique_ptr<render::FrameWriter> writer_;
  // The stability sequence being written.
  const planning::physics::SimHand* hand_ = nullptr;
  const planning::physics::SimObject* object_ = nullptr;
  planning::physics::StabilityOptions stability_;
  planning::physics::SimState last_state_;  // after the latest step
  int last_phase_ = -1;
  int last_framed_step_ = -1;         // step of the latest frame in last_phase_ (-1: none yet)
  double gravity_on_time_ = 0.0;      // simulation time at the end of closing [s]
  std::vector<int> phase_end_frame_;  // per phase 0..6: index of its last frame, -1: none
  std::vector<std::string> phase_end_label_;
  planning::physics::SimState closure_state_;  // last state of the closing phase
  std::vector<std::string> phase_outcome_;     // per phase, after FinishStability

  void AddStabilityFrame(int phase, const planning::physics::SimState& state);
};

// Hooks for RunGraspTrials: with `frames`, the frames of each trial whose method is in `framed`
// (every trial when `framed` is empty) go to OUT_DIR/frames/<grasp>_<method>/{transfer,stability}/;
// always, one progress line per trial on stderr (winding error, clearance, directions held).
planning::physics::GraspTrialHooks GraspTransferHooks(
    const std::string& out_dir, GraspFrameWriter* frames,
    const std::vector<planning::TransferMethod>& framed = {});

}  // namespace app
