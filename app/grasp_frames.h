// Frames of grasp-transfer trials, and the trial observers `grasp transfer` and the demo share.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "app/scene_builder.h"
#include "planning/grasp_transfer.h"
#include "planning/physics/grasp_trials.h"
#include "render/frames.h"
#include "render/offscreen_context.h"
#include "render/renderer.h"

namespace app {

// Renders (480x360) the human grasp, the SDH approach (AICO slices) and the final SDH grasp, then
// the ODE closing and the six gravity trials. Constructing it opens a GL context (throws
// EnvironmentError when there is none).
class GraspFrameWriter {
 public:
  GraspFrameWriter();

  // DIR/transfer_*.png: the human grasp, then every slice of transfer.trajectory; and, when the
  // trajectory is not empty, DIR/side_by_side.png (968x360): the human grasp (left) and the final
  // SDH grasp (right), seen by one camera that frames both, so both halves have the same scale.
  void Transfer(const std::string& dir, const planning::TransferSetup& setup,
                const planning::TransferResult& transfer);

  // Starts DIR/stability_*.png (+ contact sheet and video) and returns the callback for
  // TestGraspStability: a frame every 100 steps while closing (phase 0), every 250 steps of each
  // gravity direction, gravity (magnitude `gravity`, m/s²) drawn as a line. `hand` and `object`
  // must outlive the test. Call FinishStability() after the test.
  planning::physics::StepCallback Stability(const std::string& dir,
                                            const planning::physics::SimHand& hand,
                                            const planning::physics::SimObject& object,
                                            double gravity);
  void FinishStability();

 private:
  render::Image SideBySide(const render::Scene& left, const render::Scene& right,
                           const Eigen::Vector3f& view);

  render::OffscreenContext context_;
  render::Renderer renderer_;
  SceneMeshCache cache_;
  render::Camera camera_;
  Eigen::Vector3f view_ = Eigen::Vector3f(1.0f, 1.3f, 0.8f);
  bool camera_set_ = false;
  std::unique_ptr<render::FrameWriter> writer_;
};

// Hooks for RunGraspTrials: with `frames`, the frames of each trial go to
// OUT_DIR/frames/<grasp>_<method>/{transfer,stability}/; always, one progress line per trial on
// stderr (winding error, clearance, directions held).
planning::physics::GraspTrialHooks GraspTransferHooks(const std::string& out_dir,
                                                      GraspFrameWriter* frames);

}  // namespace app
