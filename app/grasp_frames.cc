#include "app/grasp_frames.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/grasp_scene.h"
#include "planning/kinematics.h"

namespace app {
namespace {

constexpr int kFrameWidth = 480;
constexpr int kFrameHeight = 360;
constexpr int kGap = 8;  // white columns between the halves of a side-by-side image

}  // namespace

GraspFrameWriter::GraspFrameWriter() : renderer_(context_.proc_loader()) {}

void GraspFrameWriter::Transfer(const std::string& dir, const planning::TransferSetup& setup,
                                const planning::TransferResult& t) {
  render::FrameWriterOptions fo;
  fo.prefix = "transfer_";
  fo.video = false;
  render::FrameWriter writer(dir, fo);
  SceneBuildOptions opt;
  opt.grid = false;
  opt.chains = true;
  // Human grasp.
  planning::KinematicsData hk(setup.human);
  planning::ForwardKinematics(setup.human, setup.human_q, &hk);
  render::Scene human;
  AddRobotShapes(setup.human, hk, Eigen::Isometry3d::Identity(), opt, &cache_, &human);
  AddGraspObjectShapes(setup.object, setup.grasp.world_from_object, &human);
  // Look at the palm from the object's side: along the SDH placement's z (palm normal), offset
  // sideways so fingers and object separate.
  const Eigen::Matrix3d rs = setup.sdh_placement.linear();
  view_ = (rs * Eigen::Vector3d(0.5, 0.6, 1.0)).cast<float>();
  camera_ = FrameSceneCamera(human, view_, 40.0f);
  writer.Add(renderer_.Render(human, camera_, kFrameWidth, kFrameHeight));
  planning::KinematicsData sk(setup.sdh);
  render::Scene last;
  for (int c = 0; c < t.trajectory.q.cols(); ++c) {
    planning::ForwardKinematics(setup.sdh, t.trajectory.q.col(c), &sk);
    render::Scene scene;
    AddRobotShapes(setup.sdh, sk, Eigen::Isometry3d::Identity(), opt, &cache_, &scene);
    AddGraspObjectShapes(setup.object, setup.grasp.world_from_object, &scene);
    if (c == 0) camera_ = FrameSceneCamera(scene, view_, 40.0f);
    writer.Add(renderer_.Render(scene, camera_, kFrameWidth, kFrameHeight));
    last = std::move(scene);
  }
  writer.Finish();
  if (t.trajectory.q.cols() > 0) {
    render::WriteFileAtomically((std::filesystem::path(dir) / "side_by_side.png").string(),
                                render::EncodePng(SideBySide(human, last, view_)));
  }
}

render::Image GraspFrameWriter::SideBySide(const render::Scene& left, const render::Scene& right,
                                           const Eigen::Vector3f& view) {
  // One camera framing both scenes (they share the world frame), so both halves have one scale.
  render::Scene both = left;
  both.shapes.insert(both.shapes.end(), right.shapes.begin(), right.shapes.end());
  both.tubes.insert(both.tubes.end(), right.tubes.begin(), right.tubes.end());
  const render::Camera camera = FrameSceneCamera(both, view, 40.0f);
  const render::Image a = renderer_.Render(left, camera, kFrameWidth, kFrameHeight);
  const render::Image b = renderer_.Render(right, camera, kFrameWidth, kFrameHeight);
  render::Image out(2 * kFrameWidth + kGap, kFrameHeight, 255, 255, 255);
  for (int y = 0; y < kFrameHeight; ++y) {
    std::copy_n(a.at(0, y), 4 * kFrameWidth, out.at(0, y));
    std::copy_n(b.at(0, y), 4 * kFrameWidth, out.at(kFrameWidth + kGap, y));
  }
  return out;
}

planning::physics::StepCallback GraspFrameWriter::Stability(
    const std::string& dir, const planning::physics::SimHand& hand,
    const planning::physics::SimObject& object, double gravity) {
  render::FrameWriterOptions fo;
  fo.prefix = "stability_";
  fo.video = true;
  writer_ = std::make_unique<render::FrameWriter>(dir, fo);
  camera_set_ = false;
  return [this, &hand, &object, gravity](int phase, const planning::physics::GraspSimulation& sim) {
    const int every = phase == 0 ? 100 : 250;
    const int step = sim.state().step;
    if (step % every != 0) return;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    if (phase > 0) {
      g[(phase - 1) / 2] = ((phase - 1) % 2 == 0 ? 1.0 : -1.0) * gravity;
      g = sim.state().world_from_link[0].linear() * g;
    }
    const render::Scene scene = GraspSimScene(hand, object, sim.state(), g);
    if (!camera_set_) {
      camera_ = FrameSceneCamera(scene, view_, 40.0f);
      camera_set_ = true;
    }
    writer_->Add(renderer_.Render(scene, camera_, kFrameWidth, kFrameHeight));
  };
}

void GraspFrameWriter::FinishStability() {
  if (writer_) writer_->Finish();
  writer_.reset();
}

planning::physics::GraspTrialHooks GraspTransferHooks(const std::string& out_dir,
                                                      GraspFrameWriter* frames) {
  namespace phys = planning::physics;
  phys::GraspTrialHooks hooks;
  if (frames) {
    hooks.on_start = [out_dir, frames](const planning::TransferSetup& setup,
                                       const planning::TransferResult& t, const phys::SimHand& hand,
                                       const phys::SimObject& object) {
      const std::string dir = (std::filesystem::path(out_dir) / "frames" /
                               (setup.grasp.name + "_" + planning::ToString(t.method)))
                                  .string();
      frames->Transfer(dir + "/transfer", setup, t);
      return frames->Stability(dir + "/stability", hand, object, phys::StabilityOptions{}.gravity);
    };
  }
  hooks.on_done = [frames](const planning::TransferSetup& setup, const phys::GraspTrial& trial) {
    if (frames) frames->FinishStability();
    const phys::StabilityResult& r = trial.stability;
    std::fprintf(stderr, "grasp %-24s %-9s winding err %.3f  clearance %+5.1f mm  %d/6 %s\n",
                 setup.grasp.name.c_str(), planning::ToString(trial.transfer.method),
                 trial.winding_error, trial.transfer.min_clearance * 1e3, r.directions_passed,
                 r.stable ? "stable" : phys::ToString(r.status));
  };
  return hooks;
}

}  // namespace app
