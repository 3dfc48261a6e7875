#include "planning/physics/stability.h"

#include <algorithm>
#include <cmath>

namespace planning::physics {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

// Object pose in the palm frame.
Eigen::Isometry3d PalmFromObject(const SimState& s) {
  return s.world_from_link[0].inverse() * s.world_from_object;
}

// Translation [m] and rotation [deg] between two palm-frame object poses.
void Drift(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double* slip, double* rot) {
  *slip = (b.translation() - a.translation()).norm();
  const Eigen::AngleAxisd d(a.linear().transpose() * b.linear());
  *rot = std::abs(d.angle()) * kRadToDeg;
}

}  // namespace

StabilityResult TestGraspStability(const OdeRuntime& runtime, const SimHand& hand,
                                   const SimObject& object, const StabilityOptions& options,
                                   const StepCallback& on_step) {
  if (!(options.close_time >= 0) || !(options.trial_time > 0) || !(options.max_slip > 0) ||
      !(options.max_rotation_deg > 0) || !std::isfinite(options.gravity)) {
    throw std::invalid_argument(
        "stability options: need close_time >= 0, trial_time > 0, "
        "max_slip > 0, max_rotation_deg > 0 and finite gravity");
  }
  GraspSimulation sim(runtime, hand, object, options.sim);
  StabilityResult result;
  static const char* kLabels[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  result.directions.resize(6);
  for (int d = 0; d < 6; ++d) {
    result.directions[d].label = kLabels[d];
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    g[d / 2] = (d % 2 == 0 ? 1.0 : -1.0) * options.gravity;
    result.directions[d].gravity_palm = g;
  }

  // Phase 1: close the hand on the object with gravity off.
  const int close_steps = static_cast<int>(std::lround(options.close_time / options.sim.dt));
  for (int k = 0; k < close_steps && !sim.state().blown_up; ++k) {
    sim.Step();
    ++result.total_steps;
    if (on_step) on_step(0, sim);
  }
  result.closure_contact_links = sim.state().num_contact_links;
  result.closure_max_depth = sim.state().max_depth;
  result.closure_contacts = sim.state().contacts;
  result.closure_world_from_object = sim.state().world_from_object;
  if (sim.state().blown_up) {
    result.status = StabilityStatus::kBlownUp;
    result.message = "closing phase: " + sim.state().blowup_reason;
    for (DirectionResult& d : result.directions) {
      d.blown_up = true;
      d.blowup_reason = result.message;
    }
    return result;
  }
  if (result.closure_contact_links < options.min_contact_links) {
    result.status = StabilityStatus::kNoGrasp;
    result.message = "after closing only " + std::to_string(result.closure_contact_links) +
                     " hand link(s) touch the object";
  }
  const Eigen::Isometry3d reference = PalmFromObject(sim.state());
  const Eigen::Matrix3d world_from_palm = sim.state().world_from_link[0].linear();
  const SimSnapshot closed = sim.SaveState();

  // Phase 2: one trial per palm axis direction, each from the post-closure state.
  const int trial_steps = static_cast<int>(std::lround(options.trial_time / options.sim.dt));
  for (int d = 0; d < 6; ++d) {
    DirectionResult& dir = result.directions[d];
    sim.RestoreState(closed);
    sim.SetGravity(world_from_palm * dir.gravity_palm);
    for (int k = 0; k < trial_steps; ++k) {
      sim.Step();
      ++dir.steps;
      if (on_step) on_step(d + 1, sim);
      if (sim.state().blown_up) break;
      double slip = 0, rot = 0;
      Drift(reference, PalmFromObject(sim.state()), &slip, &rot);
      if (slip > options.early_exit_slip) break;
    }
    result.total_steps += dir.steps;
    const SimState& s = sim.state();
    if (s.blown_up) {
      dir.blown_up = true;
      dir.blowup_reason = s.blowup_reason;
      continue;
    }
    Drift(reference, PalmFromObject(s), &dir.slip_m, &dir.rotation_deg);
    dir.contact_links = s.num_contact_links;
    dir.passed = dir.slip_m < options.max_slip && dir.rotation_deg < options.max_rotation_deg &&
                 dir.contact_links >= options.min_contact_links;
  }

  // Summary.
  bool any_blowup = false;
  for (const DirectionResult& d : result.directions) {
    if (d.blown_up) {
      any_blowup = true;
      continue;
    }
    result.directions_passed += d.passed ? 1 : 0;
    result.max_slip_m = std::max(result.max_slip_m, d.slip_m);
    result.max_rotation_deg = std::max(result.max_rotation_deg, d.rotation_deg);
  }
  if (any_blowup) {
    result.status = StabilityStatus::kBlownUp;
    for (const DirectionResult& d : result.directions) {
      if (d.blown_up) {
        result.message = "gravity " + d.label + ": " + d.blowup_reason;
        break;
      }
    }
  }
  result.stable = result.status == StabilityStatus::kTested && result.directions_passed == 6;
  return result;
}

}  // namespace planning::physics
