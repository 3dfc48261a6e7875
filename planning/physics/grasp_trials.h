// The grasp-transfer experiment as a library call: transfer human grasps to the Schunk SDH with a
// transfer method, build the ODE hand and object, and run the gravity stability test.
#pragma once

#include <functional>
#include <vector>

#include "planning/grasp.h"
#include "planning/grasp_object.h"
#include "planning/grasp_transfer.h"
#include "planning/physics/hand_builder.h"
#include "planning/physics/ode_runtime.h"
#include "planning/physics/stability.h"
#include "planning/robot.h"

namespace planning::physics {

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
};

// Observers of a trial. `on_start` runs after the transfer, once the ODE hand and object are
// built, and returns the per-step callback for the stability test (may be empty; e.g. frames or a
// recording); `on_done` runs after the stability test.
struct GraspTrialHooks {
  std::function<StepCallback(const TransferSetup& setup, const TransferResult& transfer,
                             const SimHand& hand, const SimObject& object)>
      on_start;
  std::function<void(const TransferSetup& setup, const GraspTrial& trial)> on_done;
};

// Transfers setup.grasp to the SDH with `method` (TransferGrasp), builds the ODE hand at the
// transferred q and the object at setup.grasp.world_from_object, and runs TestGraspStability.
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
};

struct GraspTrialsResult {
  std::vector<HumanGrasp> grasps;               // as given
  std::vector<TransferMethod> methods;          // as given (output order)
  StabilityOptions stability;                   // the protocol used (stability.sim.mu = mu)
  std::vector<std::vector<GraspTrial>> trials;  // trials[grasp][method]
  std::vector<GraspMethodSummary> summary;      // one per method, in `methods` order
  bool all_stable = true;                       // every trial stable
};

// Runs RunGraspTrial (kHuman: RunHumanTrial) for every grasp × method with Coulomb friction `mu`
// (default protocol otherwise), grasp-major. Each grasp's object is looked up by name in `objects`;
// `human_hand` and `sdh_source` are the robots MakeTransferSetup takes. Throws
// std::invalid_argument for an unknown object or bad grasp (as MakeTransferSetup) and for mu < 0 or
// non-finite.
GraspTrialsResult RunGraspTrials(const OdeRuntime& runtime, const Robot& human_hand,
                                 const Robot& sdh_source, const std::vector<GraspObject>& objects,
                                 const std::vector<HumanGrasp>& grasps,
                                 const std::vector<TransferMethod>& methods, double mu,
                                 const GraspTrialHooks& hooks = {});

}  // namespace planning::physics
