// Grasp stability test in ODE: close the hand with gravity off, then apply gravity along the six
// palm axes for a fixed time each and check that the object stays in the hand.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "planning/enum_names.h"
#include "planning/physics/grasp_simulation.h"

namespace planning::physics {

// Protocol (docs/methods.md §10). Pass criteria per direction, at the end of the trial:
// object translation relative to the palm < max_slip, rotation < max_rotation_deg, and at least
// min_contact_links distinct hand links touching the object.
struct StabilityOptions {
  SimOptions sim;
  double close_time = 0.5;  // phase 1, gravity off [s]
  double trial_time = 2.0;  // phase 2, per gravity direction [s]
  double gravity = 9.81;    // [m/s²]
  double max_slip = 0.02;   // [m]
  double max_rotation_deg = 15.0;
  int min_contact_links = 2;
  // A trial stops early (and fails) once the object is farther than this from its post-closure
  // pose in the palm frame: it has left the hand. Saves time; does not change pass/fail.
  double early_exit_slip = 0.1;  // [m]
};

// Outcome of one gravity direction.
struct DirectionResult {
  std::string label;                                       // "+x", "-x", "+y", "-y", "+z", "-z"
  Eigen::Vector3d gravity_palm = Eigen::Vector3d::Zero();  // gravity in the palm frame [m/s²]
  bool passed = false;
  double slip_m = 0.0;        // object translation relative to the palm at the end [m]
  double rotation_deg = 0.0;  // object rotation relative to the palm at the end [deg]
  int contact_links = 0;      // distinct hand links touching the object at the end
  bool blown_up = false;      // the simulation failed numerically; not scored
  std::string blowup_reason;
  int steps = 0;  // steps simulated (fewer than trial_time/dt after an early exit)
};

enum class StabilityStatus {
  kTested,   // closure succeeded and all six directions were simulated
  kNoGrasp,  // after closing, fewer than min_contact_links links touch the object
  kBlownUp,  // the simulation failed numerically (during closing or in some direction)
};

struct StabilityResult {
  StabilityStatus status = StabilityStatus::kTested;
  std::vector<DirectionResult> directions;  // always 6 entries (+x, −x, +y, −y, +z, −z)
  int directions_passed = 0;
  bool stable = false;             // all six passed and nothing blew up
  double max_slip_m = 0.0;         // max over directions of slip_m
  double max_rotation_deg = 0.0;   // max over directions of rotation_deg
  int closure_contact_links = 0;   // links touching after the closing phase
  double closure_max_depth = 0.0;  // deepest penetration after closing [m]
  // State at the end of the closing phase (the state every gravity direction starts from):
  // hand–object contacts (normals from the object towards the hand) and the object pose.
  std::vector<SimContact> closure_contacts;
  Eigen::Isometry3d closure_world_from_object = Eigen::Isometry3d::Identity();
  std::string message;  // human-readable reason for kNoGrasp / kBlownUp
  long total_steps = 0;
};

// Phase: 0 = closing, 1..6 = gravity direction index + 1.
using StepCallback = std::function<void(int phase, const GraspSimulation& sim)>;

// Runs the protocol: build the simulation, close for close_time with zero gravity, save the
// state, then for each direction restore it and simulate trial_time with gravity
// options.gravity along that palm axis. `on_step` (optional) is called after every step.
// Deterministic. Throws std::invalid_argument for a bad description (see GraspSimulation).
StabilityResult TestGraspStability(const OdeRuntime& runtime, const SimHand& hand,
                                   const SimObject& object, const StabilityOptions& options,
                                   const StepCallback& on_step = {});

inline constexpr EnumName<StabilityStatus> kStabilityStatusNames[] = {
    {StabilityStatus::kTested, "tested"},
    {StabilityStatus::kNoGrasp, "no_grasp"},
    {StabilityStatus::kBlownUp, "blown_up"},
};
constexpr std::span<const EnumName<StabilityStatus>> EnumNames(StabilityStatus) {
  return kStabilityStatusNames;
}
inline const char* ToString(StabilityStatus status) { return ToName(status); }

}  // namespace planning::physics
