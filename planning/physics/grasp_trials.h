// The grasp-transfer experiment as a library call: transfer human grasps to the Schunk SDH with a
// transfer method, build the ODE hand and object, and run the gravity stability test.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/hand_builder.h"
#include "planning/physics/ode_runtime.h"
#include "planning/physics/stability.h"
#include "planning/robot/robot.h"

namespace planning::physics {

// One repetition of a trial with the object moved and turned (RunGraspTrials with perturb > 0):
// the same transferred hand (or, for the human reference, the same demonstration), the object at
// world_from_object instead of the grasp's pose, the same stability protocol.
struct PerturbedTrial {
  Eigen::Isometry3d world_from_object = Eigen::Isometry3d::Identity();  // perturbed object pose
  bool stable = false;
  int directions_passed = 0;
  double epsilon_quality = 0.0;  // as GraspTrial::epsilon_quality
};

// One trial: a human grasp transferred with one method and tested in ODE.
struct GraspTrial {
  TransferResult transfer;     // SDH configuration q, windings (turns), clearance [m], solver info
  SimHand hand;                // ODE description of the SDH at transfer.q (palm link "sdh_palm")
  SimObject object;            // ODE description of the object at the grasp's world_from_object
  StabilityResult stability;   // closing phase + 6 gravity directions
  double winding_error = 0.0;  // |robot_winding − target_winding| (Euclidean, turns)
  // Ferrari–Canny ε (EpsilonQuality: L1, 8 pyramid edges, friction μ of the protocol) of the
  // contacts at the end of the closing phase (stability.closure_contacts, normals flipped to
  // point into the object) about the object's centre of mass there, torques scaled by the
  // radius of gyration ρ = sqrt(trace(I) / (3 m)) of the simulated object (ObjectMassProperties).
  // 0 without force closure, with fewer than 2 contacts or when the closing phase blew up.
  double epsilon_quality = 0.0;
  // RunHumanTrial: the demonstration itself; `transfer` then describes the human hand (q =
  // setup.human_q, all three windings = the human's, solver "demonstration", method kHuman) and
  // `hand` is the human hand (palm link "hand_palm").
  bool human = false;
  // RunGraspTrials with perturb = N > 0: the N repetitions with perturbed object poses.
  std::vector<PerturbedTrial> perturbed;
  int perturbed_stable = 0;  // repetitions whose stability test passed
};

// Observers of a trial. `on_start` runs after the transfer, once the ODE hand and object are
// built, and returns the per-step callback for the stability test (may be empty; e.g. frames or a
// recording); `on_done` runs after the stability test.
struct GraspTrialHooks {
  // Called before each stability test with the protocol it runs (`options`, the run's own), so
  // that an observer (frames) simulates and labels exactly what the verdict is made of.
  std::function<StepCallback(const TransferSetup& setup, const TransferResult& transfer,
                             const SimHand& hand, const SimObject& object,
                             const StabilityOptions& options)>
      on_start;
  std::function<void(const TransferSetup& setup, const GraspTrial& trial)> on_done;
};

// Transfers setup.grasp to the SDH with `method` (TransferGrasp), builds the ODE hand at the
// transferred q (default grip, HandBuildOptions{}.close_by) and the object at
// setup.grasp.world_from_object, and runs TestGraspStability.
// method kHuman runs RunHumanTrial instead.
GraspTrial RunGraspTrial(const OdeRuntime& runtime, const TransferSetup& setup,
                         TransferMethod method, const StabilityOptions& options,
                         const GraspTrialHooks& hooks = {});

// The human reference: simulates the demonstrated grasp itself with the same protocol. The human
// hand (setup.human) is built at setup.human_q (HumanConfiguration: palm pose and finger joints
// of the grasp file) with HumanHandBuildOptions() below "hand_palm", the object at
// setup.grasp.world_from_object; then TestGraspStability. winding_error = 0; transfer.
// min_clearance is the human hand's clearance to the object [m]. Deterministic.
GraspTrial RunHumanTrial(const OdeRuntime& runtime, const TransferSetup& setup,
                         const StabilityOptions& options, const GraspTrialHooks& hooks = {});

// Success of one method over all grasps.
struct GraspMethodSummary {
  TransferMethod method = TransferMethod::kWinding;
  int stable = 0;     // grasps whose stability test passed all 6 directions
  int grasps = 0;     // grasps tested
  double rate = 0.0;  // stable / max(1, grasps), in [0, 1]
  // Wilson 95 % interval of `rate` (WilsonInterval(stable, grasps)); (0, 1) without grasps.
  Eigen::Vector2d ci95 = Eigen::Vector2d(0.0, 1.0);
  // With perturb = N > 0: all N · grasps perturbed repetitions of this method.
  int perturbed_trials = 0;
  int perturbed_stable = 0;
  double perturbed_rate = 0.0;                                 // perturbed_stable / trials
  Eigen::Vector2d perturbed_ci95 = Eigen::Vector2d(0.0, 1.0);  // Wilson 95 %
};

// Options of RunGraspTrials beyond the grasps and methods.
struct GraspTrialsOptions {
  double mu = 1.0;  // Coulomb friction of the protocol (StabilityOptions::sim.mu)
  // Soft-finger contact patch radius of the protocol [m] (SimOptions::contact_patch_radius, the
  // same for every method and the human hand); 0 = point contacts.
  double contact_patch_radius = SimOptions{}.contact_patch_radius;
  // Grip of the protocol [rad] (HandBuildOptions::close_by, the same for every method and the
  // human hand): flexion joints are driven to their grasp value + close_by, in [0, 0.5]. Two
  // opposed fingertips whose motors both saturate hold an object in neutral balance along the
  // line between them, so gravity along that line moves it until the weaker side's finger reaches
  // this set-point: the travel grows with close_by.
  double close_by = HandBuildOptions{}.close_by;
  static constexpr double kMaxCloseBy = 0.5;  // upper bound of close_by [rad]
  // Robustness: every grasp × method is repeated `perturb` times (0: none, at most 1000) with the
  // object moved by up to perturb_translation along each world axis (uniform in [−a, a]) and
  // turned about its origin by an angle uniform in [−b, b] (b = perturb_rotation_deg) about a
  // uniformly random axis; the hand keeps its configuration (the transfer is not redone). The
  // draws of repetition k of a grasp come from std::mt19937 seeded by std::seed_seq{seed, h_lo,
  // h_hi, k} (h = FNV-1a 64 of the grasp name) through UniformUnit (planning/random.h): the same
  // for every method (paired), reproducible, independent of the other grasps and of `threads`.
  int perturb = 0;
  std::uint32_t seed = 0;
  double perturb_translation = 0.005;  // [m]
  double perturb_rotation_deg = 5.0;   // [deg]
  // Threads (>= 1): threads − 1 worker threads compute the transfers (AICO) ahead while the
  // calling thread runs every ODE simulation and every hook in grasp-major order, so results,
  // hook calls and their order do not depend on `threads`.
  int threads = 1;
  // Polled by the calling thread before each simulation; when it returns true no new trial
  // starts and RunGraspTrials returns the grasps whose trials all finished (complete = false).
  std::function<bool()> should_stop;
};

// The perturbed object pose of repetition k of grasp `grasp_name` (see GraspTrialsOptions).
Eigen::Isometry3d PerturbedObjectPose(const Eigen::Isometry3d& world_from_object,
                                      const std::string& grasp_name, int k,
                                      const GraspTrialsOptions& options);

struct GraspTrialsResult {
  std::vector<HumanGrasp> grasps;       // as given (stopped: the finished ones)
  std::vector<TransferMethod> methods;  // as given (output order)
  StabilityOptions stability;           // the protocol used (sim.mu = mu, sim.contact_patch_radius)
  double close_by = 0.0;                // GraspTrialsOptions::close_by [rad]
  std::vector<std::vector<GraspTrial>> trials;  // trials[grasp][method]
  std::vector<GraspMethodSummary> summary;      // one per method, in `methods` order
  bool all_stable = true;                       // every trial stable
  int perturb = 0;                              // GraspTrialsOptions::perturb
  std::uint32_t seed = 0;                       // GraspTrialsOptions::seed
  double perturb_translation = 0.0;             // [m]
  double perturb_rotation_deg = 0.0;            // [deg]
  bool complete = true;                         // false when should_stop ended the run early
};

// Runs RunGraspTrial (kHuman: RunHumanTrial) for every grasp × method with Coulomb friction
// options.mu (default protocol otherwise), grasp-major, then the options.perturb repetitions of
// each (see GraspTrialsOptions; on_start/on_done run for the nominal trial only). Each grasp's
// object is looked up by name in `objects`; `human_hand` and `sdh_source` are the robots
// MakeTransferSetup takes. Throws std::invalid_argument for an unknown object or bad grasp (as
// MakeTransferSetup), for mu or contact_patch_radius < 0 or non-finite, close_by outside
// [0, 0.5], perturb outside
// [0, 1000], threads < 1 or non-finite/negative perturbation sizes.
GraspTrialsResult RunGraspTrials(const OdeRuntime& runtime, const Robot& human_hand,
                                 const Robot& sdh_source, const std::vector<GraspObject>& objects,
                                 const std::vector<HumanGrasp>& grasps,
                                 const std::vector<TransferMethod>& methods,
                                 const GraspTrialsOptions& options,
                                 const GraspTrialHooks& hooks = {});

// RunGraspTrials taken apart into its independent trials, for callers that run them elsewhere
// (the demo: in forked processes). The constructor checks the options and makes every setup as
// RunGraspTrials does (the same exceptions); trial j (0 <= j < num_trials(), grasp-major: grasp
// j / methods.size(), method j % methods.size()) is RunTrial(j), the nominal trial with the hooks
// and its perturbed repetitions: exactly what RunGraspTrials computes for it, in any process and
// order. Assemble() gives RunGraspTrials' result from the trials (all of them, or with
// complete = false the finished grasps of a stopped run: the first grasps whose trials are all
// given). Keeps references to its arguments.
class GraspTrialsPlan {
 public:
  GraspTrialsPlan(const Robot& human_hand, const Robot& sdh_source,
                  const std::vector<GraspObject>& objects, const std::vector<HumanGrasp>& grasps,
                  const std::vector<TransferMethod>& methods, const GraspTrialsOptions& options);

  size_t num_trials() const { return setups_.size() * methods_.size(); }
  const TransferSetup& setup(size_t j) const { return setups_[j / methods_.size()]; }
  TransferMethod method(size_t j) const { return methods_[j % methods_.size()]; }
  GraspTrial RunTrial(const OdeRuntime& runtime, size_t j, const GraspTrialHooks& hooks) const;
  // `trials[j]` is trial j when present (nullopt: not run); the result holds the grasps before
  // the first one with a missing trial, complete = false when there is one.
  GraspTrialsResult Assemble(std::vector<std::optional<GraspTrial>> trials) const;

 private:
  const std::vector<HumanGrasp>& grasps_;
  const std::vector<TransferMethod>& methods_;
  const GraspTrialsOptions& options_;
  std::vector<TransferSetup> setups_;
  StabilityOptions stability_;
};

// The same with GraspTrialsOptions{mu}.
GraspTrialsResult RunGraspTrials(const OdeRuntime& runtime, const Robot& human_hand,
                                 const Robot& sdh_source, const std::vector<GraspObject>& objects,
                                 const std::vector<HumanGrasp>& grasps,
                                 const std::vector<TransferMethod>& methods, double mu,
                                 const GraspTrialHooks& hooks = {});

}  // namespace planning::physics
