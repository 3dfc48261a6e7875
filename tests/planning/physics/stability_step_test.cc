// StabilityRun: stepping one physics step or one phase at a time gives bit-identical results to
// TestGraspStability (the StabilityResult and the final body poses), with the phase, gravity,
// time and contacts readable between steps.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "planning/physics/stability.h"
#include "tests/planning/physics/test_hands.h"

namespace planning::physics {
namespace {

void ExpectSame(const StabilityResult& a, const StabilityResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.stable, b.stable);
  EXPECT_EQ(a.directions_passed, b.directions_passed);
  EXPECT_EQ(a.max_slip_m, b.max_slip_m);
  EXPECT_EQ(a.max_rotation_deg, b.max_rotation_deg);
  EXPECT_EQ(a.closure_contact_links, b.closure_contact_links);
  EXPECT_EQ(a.closure_max_depth, b.closure_max_depth);
  EXPECT_EQ(a.closure_contacts.size(), b.closure_contacts.size());
  EXPECT_TRUE(a.closure_world_from_object.matrix() == b.closure_world_from_object.matrix());
  EXPECT_EQ(a.total_steps, b.total_steps);
  ASSERT_EQ(a.directions.size(), b.directions.size());
  for (size_t i = 0; i < a.directions.size(); ++i) {
    EXPECT_EQ(a.directions[i].passed, b.directions[i].passed);
    EXPECT_EQ(a.directions[i].slip_m, b.directions[i].slip_m);  // bitwise
    EXPECT_EQ(a.directions[i].rotation_deg, b.directions[i].rotation_deg);
    EXPECT_EQ(a.directions[i].contact_links, b.directions[i].contact_links);
    EXPECT_EQ(a.directions[i].steps, b.directions[i].steps);
    EXPECT_EQ(a.directions[i].blown_up, b.directions[i].blown_up);
  }
}

// Body poses after a step: the hand links, then the object.
std::vector<Eigen::Matrix4d> Poses(const SimState& s) {
  std::vector<Eigen::Matrix4d> out;
  for (const Eigen::Isometry3d& t : s.world_from_link) out.push_back(t.matrix());
  out.push_back(s.world_from_object.matrix());
  return out;
}

// The program's one ODE runtime (the RAII guard allows a single instance).
OdeRuntime& Runtime() {
  static OdeRuntime runtime;
  return runtime;
}

class StabilityStepTest : public ::testing::TestWithParam<double> {};

// Closing target 1.3: an enveloping grasp; −0.3: an open hand (early exits when the bottle falls).
// PoseDrift: the distance between the two positions and the angle of the relative rotation,
// whatever the first pose.
TEST(PoseDrift, DistanceAndRelativeAngle) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity();
  a.translate(Eigen::Vector3d(0.1, -0.2, 0.3));
  a.rotate(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, -1).normalized()));
  Eigen::Isometry3d b = a;
  b.translation() += Eigen::Vector3d(0.01, 0.02, -0.02);  // 0.03 m
  b.linear() = a.linear() * Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitY()).matrix();
  double slip = -1, rotation = -1;
  PoseDrift(a, b, &slip, &rotation);
  EXPECT_NEAR(slip, 0.03, 1e-12);
  EXPECT_NEAR(rotation, 30.0, 1e-9);
  PoseDrift(a, a, &slip, &rotation);
  EXPECT_EQ(slip, 0.0);
  EXPECT_NEAR(rotation, 0.0, 1e-6);
}

TEST_P(StabilityStepTest, SteppingEqualsOneShot) {
  const SimHand hand = testing_hands::ClawHand(GetParam());
  const SimObject bottle = testing_hands::Bottle();
  StabilityOptions opt;
  opt.trial_time = 0.3;
  std::vector<Eigen::Matrix4d> one_shot_poses;
  std::vector<long> steps_per_phase(StabilityRun::kNumPhases, 0);
  const StabilityResult one_shot =
      TestGraspStability(Runtime(), hand, bottle, opt, [&](int phase, const GraspSimulation& sim) {
        one_shot_poses = Poses(sim.state());
        ++steps_per_phase[phase];
      });

  // One physics step at a time.
  StabilityRun run(Runtime(), hand, bottle, opt);
  EXPECT_EQ(run.phase(), 0);
  EXPECT_STREQ(run.phase_name(), "closing");
  EXPECT_TRUE(run.gravity().isZero());
  long steps = 0;
  while (run.StepPhysics()) {
    ++steps;
    const int phase = run.phase();
    if (phase == 0) {
      EXPECT_TRUE(run.gravity().isZero());
      EXPECT_DOUBLE_EQ(run.sim_time(), steps * opt.sim.dt);
    } else {
      EXPECT_NEAR(run.gravity().norm(), opt.gravity, 1e-12);
      EXPECT_GT(run.sim_time(), opt.close_time - 1e-9);
    }
    EXPECT_EQ(static_cast<int>(run.state().contacts.size()) > 0, run.state().num_contact_links > 0);
  }
  EXPECT_TRUE(run.done());
  EXPECT_FALSE(run.StepPhysics());  // no-op once done
  EXPECT_EQ(run.phase(), StabilityRun::kNumPhases - 1);
  ExpectSame(run.result(), one_shot);
  EXPECT_EQ(Poses(run.state()), one_shot_poses);
  long total = 0;
  for (long k : steps_per_phase) total += k;
  EXPECT_EQ(steps, total);

  // One phase at a time: seven calls, each ending its phase.
  StabilityRun phased(Runtime(), hand, bottle, opt);
  for (int p = 0; p < StabilityRun::kNumPhases; ++p) {
    phased.StepPhase();
    EXPECT_EQ(phased.phase(), p);
    EXPECT_TRUE(phased.phase_finished());
    if (p > 0) {
      EXPECT_EQ(phased.result().directions[p - 1].steps, steps_per_phase[p]);
    }
  }
  EXPECT_TRUE(phased.done());
  ExpectSame(phased.result(), one_shot);
  EXPECT_EQ(Poses(phased.state()), one_shot_poses);
}

INSTANTIATE_TEST_SUITE_P(ClosedAndOpen, StabilityStepTest, ::testing::Values(1.3, -0.3));

}  // namespace
}  // namespace planning::physics
