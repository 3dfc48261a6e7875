// The frames of a grasp trial show the simulation its verdict was made of: GraspTransferHooks hands
// the run's own StabilityOptions to the frame writer (it once used the defaults, so gravity,
// timing and outcome labels could differ from the verdict under non-default options).
#include "app/present/grasp_frames.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "planning/grasp/grasp_inputs.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/grasp_trials.h"
#include "planning/physics/ode_runtime.h"

namespace app {
namespace {

namespace phys = planning::physics;

TEST(GraspFrames, FramesOfARunWithNonDefaultOptionsShowThatRun) {
  const planning::GraspInputs in =
      planning::LoadGraspInputs(planning::SelectGraspFiles("power_bottle"));
  const planning::HumanGrasp& grasp = in.grasps.at(0);
  const planning::TransferSetup setup = planning::MakeTransferSetup(
      in.human, in.lwr_sdh, planning::FindGraspObject(in.objects, grasp.object), grasp);
  phys::StabilityOptions options;  // short and strong: not the protocol's defaults
  options.close_time = 0.3;
  options.trial_time = 0.25;
  options.gravity = 25.0;
  options.max_slip = 0.004;
  const std::string out =
      (std::filesystem::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "grasp_frames_test").string();
  std::filesystem::remove_all(out);
  GraspFrameWriter frames;
  const phys::OdeRuntime ode;
  const phys::GraspTrial trial = phys::RunGraspTrial(ode, setup, planning::TransferMethod::kHuman,
                                                     options, GraspTransferHooks(out, &frames));
  // The writer drew with the run's protocol ...
  EXPECT_EQ(frames.stability_options().gravity, options.gravity);
  EXPECT_EQ(frames.stability_options().trial_time, options.trial_time);
  EXPECT_EQ(frames.stability_options().max_slip, options.max_slip);
  // ... its last closing frame is the pose the verdict's directions start from ...
  ASSERT_EQ(trial.stability.status, phys::StabilityStatus::kTested) << trial.stability.message;
  EXPECT_NEAR(frames.closure_state().time, options.close_time, 1e-9);
  EXPECT_TRUE(frames.closure_state().world_from_object.isApprox(
      trial.stability.closure_world_from_object, 1e-12));
  // ... and every direction's label says what the verdict says, by the run's thresholds.
  const int trial_steps = static_cast<int>(options.trial_time / options.sim.dt + 0.5);
  for (size_t d = 0; d < 6; ++d) {
    const phys::DirectionResult& r = trial.stability.directions[d];
    const std::string& label = frames.phase_outcomes().at(d + 1);
    SCOPED_TRACE("direction " + r.label + ": " + label);
    EXPECT_EQ(label == "held", r.passed);
    if (!r.passed && !r.blown_up && r.steps >= trial_steps) {
      EXPECT_EQ(label.find("object dropped"), std::string::npos);  // ran its whole (short) trial
    }
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/frames/power_bottle_human/stability"));
}

}  // namespace
}  // namespace app
