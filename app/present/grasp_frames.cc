#include "app/present/grasp_frames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "base/file_write.h"
#include "planning/robot/kinematics.h"
#include "visualize/grasp_scene.h"

namespace app {
namespace {

constexpr int kFrameWidth = 480;
constexpr int kFrameHeight = 360;
constexpr int kGap = 8;  // white columns between the halves of a side-by-side image

// A 512² shadow map for the 480 × 360 frames: its depth pass was most of each frame's cost at the
// renderer's default 1024² (2,600 frames in the demo), for shadows no sharper on this frame size.
render::RenderOptions FrameOptions() {
  render::RenderOptions o;
  o.shadow_map_size = 512;
  return o;
}

}  // namespace

GraspFrameWriter::GraspFrameWriter() : renderer_(context_.proc_loader()) {}

void GraspFrameWriter::Transfer(const std::string& dir, const planning::TransferSetup& setup,
                                const planning::TransferResult& t) {
  render::FrameWriterOptions fo;
  fo.prefix = "transfer_";
  fo.video = false;
  render::FrameWriter writer(dir, fo);
  visualize::SceneBuildOptions opt;
  opt.grid = false;
  opt.chains = true;
  // Human grasp: the same frame for every method of a grasp, rendered once.
  if (!SameHumanFrame(setup)) {
    auto h = std::make_unique<HumanFrame>();
    h->grasp = setup.grasp.name;
    h->object = setup.object.name;
    h->hand = setup.human.name;
    h->q = setup.human_q;
    h->world_from_object = setup.grasp.world_from_object.matrix();
    h->sdh_placement = setup.sdh_placement.matrix();
    planning::KinematicsData hk(setup.human);
    planning::ForwardKinematics(setup.human, setup.human_q, &hk);
    visualize::AddRobotShapes(setup.human, hk, Eigen::Isometry3d::Identity(), opt, &cache_,
                              &h->scene);
    visualize::AddGraspObjectShapes(setup.object, setup.grasp.world_from_object, &h->scene);
    // Look at the palm from the object's side: along the SDH placement's z (palm normal), offset
    // sideways so fingers and object separate.
    const Eigen::Matrix3d rs = setup.sdh_placement.linear();
    h->view = (rs * Eigen::Vector3d(0.5, 0.6, 1.0)).cast<float>();
    h->camera = visualize::FrameSceneCamera(h->scene, h->view, 40.0f);
    h->image = renderer_.Render(h->scene, h->camera, kFrameWidth, kFrameHeight, FrameOptions());
    render::DrawStamp(&h->image, {setup.grasp.name + ": human grasp"});
    human_frame_ = std::move(h);
  }
  const render::Scene& human = human_frame_->scene;
  view_ = human_frame_->view;
  camera_ = human_frame_->camera;
  writer.Add(human_frame_->image, "human grasp");
  planning::KinematicsData sk(setup.sdh);
  render::Scene last;
  for (int c = 0; c < t.trajectory.q.cols(); ++c) {
    planning::ForwardKinematics(setup.sdh, t.trajectory.q.col(c), &sk);
    render::Scene scene;
    visualize::AddRobotShapes(setup.sdh, sk, Eigen::Isometry3d::Identity(), opt, &cache_, &scene);
    visualize::AddGraspObjectShapes(setup.object, setup.grasp.world_from_object, &scene);
    if (c == 0) camera_ = visualize::FrameSceneCamera(scene, view_, 40.0f);
    // AICO time slices of the approach: their time when the trajectory has one, else the index.
    char label[64];
    if (t.trajectory.dt > 0.0) {
      std::snprintf(label, sizeof label, "SDH, t = %.2f s", c * t.trajectory.dt);
    } else {
      std::snprintf(label, sizeof label, "SDH, slice %d", c);
    }
    render::Image frame =
        renderer_.Render(scene, camera_, kFrameWidth, kFrameHeight, FrameOptions());
    render::DrawStamp(&frame, {setup.grasp.name + ": " + planning::ToString(t.method), label});
    writer.Add(frame, label);
    last = std::move(scene);
  }
  writer.Finish();
  if (t.trajectory.q.cols() > 0) {
    base::WriteFileAtomic((std::filesystem::path(dir) / "side_by_side.png").string(),
                          render::EncodePng(SideBySide(human, last, view_)));
  }
}

bool GraspFrameWriter::SameHumanFrame(const planning::TransferSetup& setup) const {
  const HumanFrame* h = human_frame_.get();
  return h != nullptr && h->grasp == setup.grasp.name && h->object == setup.object.name &&
         h->hand == setup.human.name && h->q.size() == setup.human_q.size() &&
         h->q == setup.human_q && h->world_from_object == setup.grasp.world_from_object.matrix() &&
         h->sdh_placement == setup.sdh_placement.matrix();
}

render::Image GraspFrameWriter::SideBySide(const render::Scene& left, const render::Scene& right,
                                           const Eigen::Vector3f& view) {
  // One camera framing both scenes (they share the world frame), so both halves have one scale.
  render::Scene both = left;
  both.shapes.insert(both.shapes.end(), right.shapes.begin(), right.shapes.end());
  both.tubes.insert(both.tubes.end(), right.tubes.begin(), right.tubes.end());
  const render::Camera camera = visualize::FrameSceneCamera(both, view, 40.0f);
  const render::Image a = renderer_.Render(left, camera, kFrameWidth, kFrameHeight, FrameOptions());
  const render::Image b =
      renderer_.Render(right, camera, kFrameWidth, kFrameHeight, FrameOptions());
  render::Image out(2 * kFrameWidth + kGap, kFrameHeight, 255, 255, 255);
  for (int y = 0; y < kFrameHeight; ++y) {
    std::copy_n(a.at(0, y), 4 * kFrameWidth, out.at(0, y));
    std::copy_n(b.at(0, y), 4 * kFrameWidth, out.at(kFrameWidth + kGap, y));
  }
  return out;
}

namespace {

namespace phys = planning::physics;

// "closing" for phase 0, else the gravity direction in the palm frame ("+x" … "−z").
std::string PhaseText(int phase) {
  if (phase == 0) return "closing";
  const char* axis[] = {"x", "y", "z"};
  return std::string("g = ") + ((phase - 1) % 2 == 0 ? "+" : "\u2212") + axis[(phase - 1) / 2];
}

// How gravity direction `d` ended, for the label of its last frame.
std::string DirectionOutcome(const phys::DirectionResult& d, const phys::StabilityOptions& o) {
  char buf[96];
  if (d.blown_up) return "simulation blew up";
  if (d.passed) return "held";
  const int trial_steps = static_cast<int>(std::lround(o.trial_time / o.sim.dt));
  if (d.steps < trial_steps) {
    std::snprintf(buf, sizeof buf, "object dropped (%.0f mm away)", d.slip_m * 1e3);
  } else if (d.slip_m >= o.max_slip) {
    std::snprintf(buf, sizeof buf, "slipped %.0f mm (max %.0f)", d.slip_m * 1e3, o.max_slip * 1e3);
  } else if (d.rotation_deg >= o.max_rotation_deg) {
    std::snprintf(buf, sizeof buf, "rotated %.0f\u00b0 (max %.0f)", d.rotation_deg,
                  o.max_rotation_deg);
  } else {
    std::snprintf(buf, sizeof buf, "%d link(s) in contact (min %d)", d.contact_links,
                  o.min_contact_links);
  }
  return buf;
}

}  // namespace

void GraspFrameWriter::AddStabilityFrame(int phase, const phys::SimState& state) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  if (phase > 0) {
    g[(phase - 1) / 2] = ((phase - 1) % 2 == 0 ? 1.0 : -1.0) * stability_.gravity;
    g = state.world_from_link[0].linear() * g;
  }
  const render::Scene scene = visualize::GraspSimScene(*hand_, *object_, state, g);
  if (!camera_set_) {
    camera_ = visualize::FrameSceneCamera(scene, view_, 40.0f);
    camera_set_ = true;
  }
  char time[48];
  std::snprintf(time, sizeof time, "t = %.2f s",
                phase == 0 ? state.time : state.time - gravity_on_time_);
  const std::string label = std::string(time) + ", " + PhaseText(phase);
  render::Image frame = renderer_.Render(scene, camera_, kFrameWidth, kFrameHeight, FrameOptions());
  render::DrawStamp(&frame, {label});
  writer_->Add(frame, label);
  phase_end_frame_[static_cast<size_t>(phase)] = writer_->size() - 1;
  phase_end_label_[static_cast<size_t>(phase)] = label;
  last_framed_step_ = state.step;
}

phys::StepCallback GraspFrameWriter::Stability(const std::string& dir, const phys::SimHand& hand,
                                               const phys::SimObject& object,
                                               const phys::StabilityOptions& options) {
  std::function<void(int, const phys::SimState&)> states =
      StabilityStates(dir, hand, object, options);
  return [states](int phase, const phys::GraspSimulation& sim) { states(phase, sim.state()); };
}

std::function<void(int, const phys::SimState&)> GraspFrameWriter::StabilityStates(
    const std::string& dir, const phys::SimHand& hand, const phys::SimObject& object,
    const phys::StabilityOptions& options) {
  render::FrameWriterOptions fo;
  fo.prefix = "stability_";
  fo.video = true;
  fo.video_batch = batch_videos_ ? &videos_ : nullptr;
  writer_ = std::make_unique<render::FrameWriter>(dir, fo);
  camera_set_ = false;
  hand_ = &hand;
  object_ = &object;
  stability_ = options;
  last_phase_ = -1;
  last_framed_step_ = -1;
  gravity_on_time_ = 0.0;
  phase_end_frame_.assign(7, -1);
  phase_end_label_.assign(7, "");
  phase_outcome_.assign(7, "");
  closure_state_ = phys::SimState{};
  return [this](int phase, const phys::SimState& state) {
    if (phase != last_phase_) {
      // The previous phase ended: show its last state unless it is already a frame.
      if (last_phase_ >= 0 && last_framed_step_ != last_state_.step) {
        AddStabilityFrame(last_phase_, last_state_);
      }
      if (last_phase_ == 0) {
        gravity_on_time_ = last_state_.time;
        closure_state_ = last_state_;
      }
      last_phase_ = phase;
      last_framed_step_ = -1;
    }
    last_state_ = state;
    const int every = phase == 0 ? 100 : 250;
    if (state.step % every == 0) AddStabilityFrame(phase, state);
  };
}

void GraspFrameWriter::FinishStability(const phys::StabilityResult& result) {
  if (!writer_) return;
  if (last_phase_ >= 0 && last_framed_step_ != last_state_.step) {
    AddStabilityFrame(last_phase_, last_state_);
  }
  // Why each phase ended, under its last frame (always on the contact sheet).
  std::string closing;
  if (result.status == phys::StabilityStatus::kNoGrasp ||
      (result.status == phys::StabilityStatus::kBlownUp && last_phase_ == 0)) {
    closing = result.message;
  }
  for (int phase = 0; phase < 7; ++phase) {
    const int frame = phase_end_frame_[static_cast<size_t>(phase)];
    if (frame < 0) continue;
    // A closing phase that blew up ends the protocol: its message says so.
    const std::string why =
        phase == 0
            ? (closing.empty() ? "closed" : closing)
            : DirectionOutcome(result.directions[static_cast<size_t>(phase - 1)], stability_);
    phase_outcome_[static_cast<size_t>(phase)] = why;
    writer_->SetLabel(frame, phase_end_label_[static_cast<size_t>(phase)] + "\n" + why, true);
  }
  writer_->Finish();
  writer_.reset();
}

planning::physics::GraspTrialHooks GraspTransferHooks(
    const std::string& out_dir, GraspFrameWriter* frames,
    const std::vector<planning::TransferMethod>& framed) {
  namespace phys = planning::physics;
  phys::GraspTrialHooks hooks;
  const auto drawn = [framed](planning::TransferMethod m) {
    return framed.empty() || std::find(framed.begin(), framed.end(), m) != framed.end();
  };
  if (frames) {
    hooks.on_start = [out_dir, frames, drawn](
                         const planning::TransferSetup& setup, const planning::TransferResult& t,
                         const phys::SimHand& hand, const phys::SimObject& object,
                         const phys::StabilityOptions& options) -> phys::StepCallback {
      if (!drawn(t.method)) return {};
      const std::string dir =
          (std::filesystem::path(out_dir) / "frames" /
           base::SafeFileName(setup.grasp.name + "_" + planning::ToString(t.method), "grasp name"))
              .string();
      frames->Transfer(dir + "/transfer", setup, t);
      return frames->Stability(dir + "/stability", hand, object, options);
    };
  }
  hooks.on_done = [frames, drawn](const planning::TransferSetup& setup,
                                  const phys::GraspTrial& trial) {
    if (frames && drawn(trial.transfer.method)) frames->FinishStability(trial.stability);
    const phys::StabilityResult& r = trial.stability;
    std::fprintf(stderr, "grasp %-24s %-9s winding err %.3f  clearance %+5.1f mm  %d/6 %s\n",
                 setup.grasp.name.c_str(), planning::ToString(trial.transfer.method),
                 trial.winding_error, trial.transfer.min_clearance * 1e3, r.directions_passed,
                 r.stable ? "stable" : phys::ToString(r.status));
  };
  return hooks;
}

}  // namespace app
