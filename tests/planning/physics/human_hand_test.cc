// The human hand in ODE: the motor torque at a joint stop (the cause of the human hand's
// blow-ups) and the demonstrated power grasp under the stability protocol.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/grasp_trials.h"
#include "planning/physics/hand_builder.h"
#include "planning/robot/robot_io.h"
#include "tests/planning/physics/test_hands.h"

namespace planning::physics {
namespace {

const std::string kAssets = std::string(TOPOPLAN_SOURCE_DIR) + "/assets/";

// The claw hand's palm and first phalanx, made a 4 g link (capsule r 9 mm, 45 mm: inertia about
// the hinge ≈ 3e-6 kg m²) that sits at its lower stop and is commanded to close with a 5 N m
// motor; the object is far away.
SimHand PhalanxAtStop(bool limit_stop_torque) {
  SimHand hand = testing_hands::ClawHand(1.0);
  hand.links.resize(2);
  hand.limit_stop_torque = limit_stop_torque;
  SimHandLink& link = hand.links[1];
  link.lower = link.q_start;
  link.max_torque = 5.0;
  link.mass = 0.004;
  return hand;
}

SimObject FarBall() {
  SimObject o;
  SimShape s;
  s.kind = SimShape::Kind::kSphere;
  s.size = Eigen::Vector3d(0.02, 0, 0);
  o.shapes.push_back(s);
  o.world_from_object.translation() = Eigen::Vector3d(1, 1, 1);
  return o;
}

// Joint speed after one step [rad/s].
double FirstStepSpeed(const OdeRuntime& runtime, bool limit_stop_torque) {
  GraspSimulation sim(runtime, PhalanxAtStop(limit_stop_torque), FarBall(), {});
  sim.Step();
  return std::abs(sim.state().joint_angles[1]) / SimOptions{}.dt;
}

TEST(HumanHandTest, MotorAtAStopNoLongerThrowsALightLink) {
  OdeRuntime runtime;
  std::printf("first-step joint speed: plain %.1f rad/s, limited %.3f rad/s\n",
              FirstStepSpeed(runtime, false), FirstStepSpeed(runtime, true));
  // ODE's plain behaviour: 5 N m open-loop on ≈ 1e-6 kg m² for 1 ms, over a thousand rad/s.
  EXPECT_GT(FirstStepSpeed(runtime, false), 500.0);
  // Limited: the joint leaves the stop at about the commanded speed (≤ max_joint_speed).
  EXPECT_LT(FirstStepSpeed(runtime, true), 2.0 * SimOptions{}.max_joint_speed);
}

TEST(HumanHandTest, HumanHandStaysFiniteAndHoldsThePowerGrasp) {
  const Robot human = LoadRobot(kAssets + "robots/human_hand.urdf");
  const Robot lwr = LoadRobot(kAssets + "robots/lwr4_sdh.urdf");
  const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  const HumanGrasp grasp = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  const TransferSetup setup =
      MakeTransferSetup(human, lwr, FindGraspObject(objects, grasp.object), grasp);
  OdeRuntime runtime;
  StabilityOptions options;
  options.sim.mu = 1.0;
  double max_speed = 0.0;
  bool finite = true;
  GraspTrialHooks hooks;
  hooks.on_start = [&](const TransferSetup&, const TransferResult&, const SimHand&,
                       const SimObject&, const StabilityOptions&) -> StepCallback {
    return [&](int, const GraspSimulation& sim) {
      const SimState& s = sim.state();
      finite = finite && s.world_from_object.matrix().allFinite();
      for (const Eigen::Isometry3d& t : s.world_from_link) {
        finite = finite && t.matrix().allFinite();
      }
      max_speed = std::max(max_speed, s.object_linear_velocity.norm());
    };
  };
  const GraspTrial trial = RunHumanTrial(runtime, setup, options, hooks);
  EXPECT_TRUE(trial.human);
  EXPECT_EQ(trial.hand.links[0].name, "hand_palm");
  EXPECT_TRUE(finite);
  EXPECT_LT(max_speed, 1.0);  // m/s: nothing is thrown
  EXPECT_NE(trial.stability.status, StabilityStatus::kBlownUp) << trial.stability.message;
  EXPECT_TRUE(trial.stability.stable)
      << trial.stability.directions_passed << "/6, max slip " << trial.stability.max_slip_m;
  EXPECT_GE(trial.stability.closure_contact_links, 5);
  EXPECT_EQ(trial.winding_error, 0.0);
  ASSERT_EQ(trial.transfer.human_winding.size(), 5);
  EXPECT_GT(trial.transfer.human_winding.cwiseAbs().maxCoeff(), 0.3);  // fingers wrap the bottle
  EXPECT_EQ(trial.transfer.method, TransferMethod::kHuman);
  // Five fingers around the bottle with mu = 1: force closure at the end of closing.
  EXPECT_GT(trial.epsilon_quality, 0.0);
  EXPECT_LT(trial.epsilon_quality, 1.0);
}

}  // namespace
}  // namespace planning::physics
