#include "planning/physics/stability.h"

#include <algorithm>
#include <cmath>

namespace planning::physics {
namespace {

// Object pose in the palm frame.
Eigen::Isometry3d PalmFromObject(const SimState& s) {
  return s.world_from_link[0].inverse() * s.world_from_object;
}

void CheckOptions(const StabilityOptions& options) {
  if (!(options.close_time >= 0) || !(options.trial_time > 0) || !(options.max_slip > 0) ||
      !(options.max_rotation_deg > 0) || !std::isfinite(options.gravity)) {
    throw std::invalid_argument(
        "stability options: need close_time >= 0, trial_time > 0, "
        "max_slip > 0, max_rotation_deg > 0 and finite gravity");
  }
}

const StabilityOptions& Checked(const StabilityOptions& options) {
  CheckOptions(options);
  return options;
}

}  // namespace

void PoseDrift(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double* slip_m,
               double* rotation_deg) {
  constexpr double kRadToDeg = 57.29577951308232;
  *slip_m = (b.translation() - a.translation()).norm();
  const Eigen::AngleAxisd d(a.linear().transpose() * b.linear());
  *rotation_deg = std::abs(d.angle()) * kRadToDeg;
}

StabilityRun::StabilityRun(const OdeRuntime& runtime, const SimHand& hand, const SimObject& object,
                           const StabilityOptions& options, const StepCallback& on_step)
    : options_(Checked(options)), on_step_(on_step), sim_(runtime, hand, object, options.sim) {
  static const char* kLabels[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  result_.directions.resize(6);
  for (int d = 0; d < 6; ++d) {
    result_.directions[d].label = kLabels[d];
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    g[d / 2] = (d % 2 == 0 ? 1.0 : -1.0) * options_.gravity;
    result_.directions[d].gravity_palm = g;
  }
  close_steps_ = static_cast<int>(std::lround(options_.close_time / options_.sim.dt));
  trial_steps_ = static_cast<int>(std::lround(options_.trial_time / options_.sim.dt));
  CheckPhaseEnd();  // a closing phase of zero steps ends at once
}

const char* StabilityRun::phase_name() const {
  static const char* kNames[kNumPhases] = {"closing",    "gravity +x", "gravity -x", "gravity +y",
                                           "gravity -y", "gravity +z", "gravity -z"};
  return kNames[phase_];
}

double StabilityRun::sim_time() const {
  const int steps =
      phase_ == 0 ? closing_done_ : closing_done_ + result_.directions[phase_ - 1].steps;
  return steps * options_.sim.dt;
}

bool StabilityRun::StepPhysics() {
  while (!done_ && phase_finished_) BeginNextPhase();
  if (done_) return false;
  sim_.Step();
  if (phase_ == 0) {
    ++closing_done_;
    ++result_.total_steps;
  } else {
    ++result_.directions[phase_ - 1].steps;
  }
  if (on_step_) on_step_(phase_, sim_);
  CheckPhaseEnd();
  return true;
}

void StabilityRun::StepPhase() {
  if (done_) return;
  const int target = phase_finished_ ? phase_ + 1 : phase_;
  while (!done_ && (phase_ < target || (phase_ == target && !phase_finished_))) StepPhysics();
}

// Records the end of the current phase if it has ended (reads the simulation only).
void StabilityRun::CheckPhaseEnd() {
  const SimState& s = sim_.state();
  if (phase_ == 0) {
    if (closing_done_ < close_steps_ && !s.blown_up) return;
    phase_finished_ = true;
    result_.closure_contact_links = s.num_contact_links;
    result_.closure_max_depth = s.max_depth;
    result_.closure_contacts = s.contacts;
    result_.closure_world_from_object = s.world_from_object;
    if (s.blown_up) {
      result_.status = StabilityStatus::kBlownUp;
      result_.message = "closing phase: " + s.blowup_reason;
      for (DirectionResult& d : result_.directions) {
        d.blown_up = true;
        d.blowup_reason = result_.message;
      }
      done_ = true;
      return;
    }
    if (result_.closure_contact_links < options_.min_contact_links) {
      result_.status = StabilityStatus::kNoGrasp;
      result_.message = "after closing only " + std::to_string(result_.closure_contact_links) +
                        " hand link(s) touch the object";
    }
    reference_ = PalmFromObject(s);
    world_from_palm_ = s.world_from_link[0].linear();
    closed_ = sim_.SaveState();
    return;
  }
  DirectionResult& dir = result_.directions[phase_ - 1];
  if (dir.steps < trial_steps_ && !s.blown_up) {
    if (dir.steps == 0) return;
    double slip = 0, rot = 0;
    PoseDrift(reference_, PalmFromObject(s), &slip, &rot);
    if (!(slip > options_.early_exit_slip)) return;
  }
  phase_finished_ = true;
  result_.total_steps += dir.steps;
  if (s.blown_up) {
    dir.blown_up = true;
    dir.blowup_reason = s.blowup_reason;
  } else {
    PoseDrift(reference_, PalmFromObject(s), &dir.slip_m, &dir.rotation_deg);
    dir.contact_links = s.num_contact_links;
    dir.passed = dir.slip_m < options_.max_slip && dir.rotation_deg < options_.max_rotation_deg &&
                 dir.contact_links >= options_.min_contact_links;
  }
  if (phase_ == kNumPhases - 1) Summarise();
}

// From a finished phase to the next gravity direction: the post-closure state, its gravity.
void StabilityRun::BeginNextPhase() {
  ++phase_;
  phase_finished_ = false;
  DirectionResult& dir = result_.directions[phase_ - 1];
  sim_.RestoreState(closed_);
  gravity_ = world_from_palm_ * dir.gravity_palm;
  sim_.SetGravity(gravity_);
  CheckPhaseEnd();  // a trial of zero steps ends at once
}

void StabilityRun::Summarise() {
  bool any_blowup = false;
  for (const DirectionResult& d : result_.directions) {
    if (d.blown_up) {
      any_blowup = true;
      continue;
    }
    result_.directions_passed += d.passed ? 1 : 0;
    result_.max_slip_m = std::max(result_.max_slip_m, d.slip_m);
    result_.max_rotation_deg = std::max(result_.max_rotation_deg, d.rotation_deg);
  }
  if (any_blowup) {
    result_.status = StabilityStatus::kBlownUp;
    for (const DirectionResult& d : result_.directions) {
      if (d.blown_up) {
        result_.message = "gravity " + d.label + ": " + d.blowup_reason;
        break;
      }
    }
  }
  result_.stable = result_.status == StabilityStatus::kTested && result_.directions_passed == 6;
  done_ = true;
}

StabilityResult TestGraspStability(const OdeRuntime& runtime, const SimHand& hand,
                                   const SimObject& object, const StabilityOptions& options,
                                   const StepCallback& on_step) {
  StabilityRun run(runtime, hand, object, options, on_step);
  while (run.StepPhysics()) {
  }
  return run.result();
}

}  // namespace planning::physics
