// Grasp stability test in ODE: close the hand with gravity off, then apply gravity along the six
// palm axes for a fixed time each and check that the object stays in the hand.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "base/enum_names.h"
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

// The protocol as a resumable run: StepPhysics() advances one physics step, StepPhase() to the end
// of the current phase (closing, or one gravity direction); the simulation (bodies, contacts),
// the applied gravity, the phase and the simulated time are readable between steps. A phase's
// end is recorded right after its last step; the next phase's set-up (restoring the post-closure
// state, setting its gravity) happens at the start of the next step, so between steps the
// simulation always shows the state just simulated. Stepping to the end gives bit-identical
// results to TestGraspStability. Keeps references to `runtime` (must outlive the run); copies
// the options. Throws std::invalid_argument as TestGraspStability.
class StabilityRun {
 public:
  static constexpr int kNumPhases = 7;  // 0 = closing, 1..6 = gravity +x, −x, +y, −y, +z, −z

  StabilityRun(const OdeRuntime& runtime, const SimHand& hand, const SimObject& object,
               const StabilityOptions& options, const StepCallback& on_step = {});

  // One physics step (after setting up the next phase if the current one has ended). Returns
  // false, doing nothing, once done().
  bool StepPhysics();
  // Steps until the phase being simulated ends (a finished phase: the next one). No-op if done().
  void StepPhase();

  bool done() const { return done_; }
  int phase() const { return phase_; }  // 0..6 as kNumPhases
  bool phase_finished() const { return phase_finished_; }
  const char* phase_name() const;  // "closing", "gravity +x", ...
  // Simulated time of the current state [s]: from the start of closing along this phase's branch
  // (closing time + trial time in a gravity phase).
  double sim_time() const;
  // World-frame gravity now applied [m/s²] (zero while closing).
  const Eigen::Vector3d& gravity() const { return gravity_; }
  const GraspSimulation& simulation() const { return sim_; }
  const SimState& state() const { return sim_.state(); }  // bodies, joints, contacts
  // The result so far: closure fields once closing ended, direction entries once each ended;
  // final (summary filled) once done().
  const StabilityResult& result() const { return result_; }

 private:
  void CheckPhaseEnd();
  void BeginNextPhase();
  void Summarise();

  StabilityOptions options_;
  StepCallback on_step_;
  GraspSimulation sim_;
  StabilityResult result_;
  int close_steps_ = 0, trial_steps_ = 0, closing_done_ = 0;
  int phase_ = 0;
  bool phase_finished_ = false, done_ = false;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  Eigen::Isometry3d reference_ = Eigen::Isometry3d::Identity();  // post-closure palm-from-object
  Eigen::Matrix3d world_from_palm_ = Eigen::Matrix3d::Identity();
  SimSnapshot closed_;
};

// Runs the protocol: build the simulation, close for close_time with zero gravity, save the
// state, then for each direction restore it and simulate trial_time with gravity
// options.gravity along that palm axis. `on_step` (optional) is called after every step.
// Deterministic. A loop over StabilityRun::StepPhysics. Throws std::invalid_argument for a bad
// description (see GraspSimulation).
StabilityResult TestGraspStability(const OdeRuntime& runtime, const SimHand& hand,
                                   const SimObject& object, const StabilityOptions& options,
                                   const StepCallback& on_step = {});

// How far an object moved between two of its poses in the palm frame, a → b: the translation
// |b.t − a.t| [m] and the rotation angle of a.R⁻¹·b.R [deg] (the slip and rotation that ODE's and
// MuJoCo's trials judge).
void PoseDrift(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double* slip_m,
               double* rotation_deg);

inline constexpr base::EnumName<StabilityStatus> kStabilityStatusNames[] = {
    {StabilityStatus::kTested, "tested"},
    {StabilityStatus::kNoGrasp, "no_grasp"},
    {StabilityStatus::kBlownUp, "blown_up"},
};
constexpr std::span<const base::EnumName<StabilityStatus>> EnumNames(StabilityStatus) {
  return kStabilityStatusNames;
}
inline const char* ToString(StabilityStatus status) { return base::ToName(status); }

}  // namespace planning::physics
