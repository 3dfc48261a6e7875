#include "planning/physics/grasp_trials.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "planning/grasp_quality.h"
#include "planning/kinematics.h"

namespace planning::physics {
namespace {

// GraspTrial::epsilon_quality of a finished stability test.
double ClosureEpsilon(const SimObject& object, const StabilityResult& r, double mu) {
  if (r.status == StabilityStatus::kBlownUp && r.message.rfind("closing", 0) == 0) return 0.0;
  std::vector<GraspContact> contacts;
  for (const SimContact& c : r.closure_contacts) {
    if (!c.position.allFinite() || !c.normal.allFinite() || !(c.normal.norm() > 1e-12)) continue;
    contacts.push_back({c.position, -c.normal});
  }
  const ObjectMass mass = ObjectMassProperties(object);
  EpsilonOptions eo;
  eo.radius_of_gyration = std::sqrt(mass.inertia.trace() / (3.0 * mass.mass));
  return EpsilonQuality(contacts, r.closure_world_from_object * mass.com, mu, eo);
}

// Runs the stability test on trial->hand and trial->object, with the hooks around it.
void Simulate(const OdeRuntime& runtime, const TransferSetup& setup,
              const StabilityOptions& options, const GraspTrialHooks& hooks, GraspTrial* trial) {
  StepCallback on_step;
  if (hooks.on_start) on_step = hooks.on_start(setup, trial->transfer, trial->hand, trial->object);
  trial->stability = TestGraspStability(runtime, trial->hand, trial->object, options, on_step);
  trial->epsilon_quality = ClosureEpsilon(trial->object, trial->stability, options.sim.mu);
  if (hooks.on_done) hooks.on_done(setup, *trial);
}

}  // namespace

GraspTrial RunGraspTrial(const OdeRuntime& runtime, const TransferSetup& setup,
                         TransferMethod method, const StabilityOptions& options,
                         const GraspTrialHooks& hooks) {
  if (method == TransferMethod::kHuman) return RunHumanTrial(runtime, setup, options, hooks);
  GraspTrial trial;
  trial.transfer = TransferGrasp(setup, method);
  trial.winding_error = (trial.transfer.robot_winding - trial.transfer.target_winding).norm();
  trial.hand = BuildSimHand(setup.sdh, trial.transfer.q, "sdh_palm");
  trial.object = BuildSimObject(setup.object, setup.grasp.world_from_object);
  Simulate(runtime, setup, options, hooks, &trial);
  return trial;
}

GraspTrial RunHumanTrial(const OdeRuntime& runtime, const TransferSetup& setup,
                         const StabilityOptions& options, const GraspTrialHooks& hooks) {
  GraspTrial trial;
  trial.human = true;
  TransferResult& t = trial.transfer;
  t.method = TransferMethod::kHuman;
  t.q = setup.human_q;
  KinematicsData kin(setup.human);
  ForwardKinematics(setup.human, setup.human_q, &kin);
  const GraspEncoding enc = EncodeGrasp(setup.human, kin, setup.human_chains, setup.reference);
  t.human_winding = t.target_winding = t.robot_winding = enc.finger;
  t.human_phalanx_winding = t.robot_phalanx_winding = enc.phalanx;
  t.min_clearance = HandClearance(setup.human, kin, SampleHandSpheres(setup.human, {}, 0.002),
                                  setup.object, setup.grasp.world_from_object);
  t.solver = "demonstration";
  t.iterations = 0;
  trial.hand = BuildSimHand(setup.human, setup.human_q, "hand_palm", HumanHandBuildOptions());
  trial.object = BuildSimObject(setup.object, setup.grasp.world_from_object);
  Simulate(runtime, setup, options, hooks, &trial);
  return trial;
}

GraspTrialsResult RunGraspTrials(const OdeRuntime& runtime, const Robot& human_hand,
                                 const Robot& sdh_source, const std::vector<GraspObject>& objects,
                                 const std::vector<HumanGrasp>& grasps,
                                 const std::vector<TransferMethod>& methods, double mu,
                                 const GraspTrialHooks& hooks) {
  if (!(mu >= 0) || !std::isfinite(mu)) {
    throw std::invalid_argument("grasp trials: mu must be a finite number >= 0");
  }
  GraspTrialsResult result;
  result.grasps = grasps;
  result.methods = methods;
  result.stability.sim.mu = mu;
  for (TransferMethod m : methods) {
    GraspMethodSummary s;
    s.method = m;
    s.grasps = static_cast<int>(grasps.size());
    result.summary.push_back(s);
  }
  for (const HumanGrasp& g : grasps) {
    const GraspObject& object = FindGraspObject(objects, g.object);
    const TransferSetup setup = MakeTransferSetup(human_hand, sdh_source, object, g);
    std::vector<GraspTrial>& row = result.trials.emplace_back();
    for (size_t mi = 0; mi < methods.size(); ++mi) {
      row.push_back(RunGraspTrial(runtime, setup, methods[mi], result.stability, hooks));
      const bool stable = row.back().stability.stable;
      result.summary[mi].stable += stable ? 1 : 0;
      result.all_stable = result.all_stable && stable;
    }
  }
  for (GraspMethodSummary& s : result.summary) {
    s.rate = static_cast<double>(s.stable) / std::max(1, s.grasps);
  }
  return result;
}

}  // namespace planning::physics
