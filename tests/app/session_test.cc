#include "app/session.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace app {
namespace {

class SessionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1);
    session_.Apply(SessionCommand(SessionCommand::Kind::kLoad, "unwrap"), &settings_);
  }
  Session session_;
  Settings settings_;
};

TEST_F(SessionTest, LoadsScenarioWithStartConfigurationAndWrithe) {
  ASSERT_TRUE(session_.has_scenario());
  EXPECT_EQ(session_.num_frames(settings_), 0);
  EXPECT_EQ(session_.ShownQ(settings_).size(), 27);  // 20 arm joints + 7 SDH joints
  const Eigen::MatrixXd w = session_.WritheAt(session_.ShownQ(settings_));
  EXPECT_EQ(w.rows(), 20);
  EXPECT_GT(std::abs(w.sum()), 1.0);  // the start coil wraps the pole
}

TEST_F(SessionTest, StepShowsSweepsInOrderAndPlanShowsTheResult) {
  session_.Apply(SessionCommand(SessionCommand::Kind::kStep), &settings_);
  ASSERT_FALSE(session_.sweeps().empty());
  EXPECT_EQ(settings_.sweep, 0);
  const Eigen::VectorXd q_sweep0 = session_.ShownQ(settings_);
  session_.Apply(SessionCommand(SessionCommand::Kind::kStep), &settings_);
  EXPECT_EQ(settings_.sweep, 1);
  // Stepping through every recorded sweep moves the shown end configuration.
  double moved = 0.0;
  for (size_t k = 1; k < session_.sweeps().size(); ++k) {
    session_.Apply(SessionCommand(SessionCommand::Kind::kStep), &settings_);
    moved = std::max(moved, (session_.ShownQ(settings_) - q_sweep0).norm());
  }
  EXPECT_EQ(settings_.sweep, static_cast<int>(session_.sweeps().size()) - 1);
  EXPECT_GT(moved, 0.1);
  // The final trajectory (sweep −1) ends unwrapped.
  settings_.sweep = -1;
  session_.Apply(SessionCommand(SessionCommand::Kind::kSeek, "", 0, 1e9), &settings_);
  EXPECT_EQ(settings_.frame, session_.num_frames(settings_) - 1);
  EXPECT_LT(std::abs(session_.WritheAt(session_.ShownQ(settings_)).sum()), 0.1);
  ASSERT_TRUE(session_.result().has_value());
  EXPECT_TRUE(session_.result()->report.success);
}

TEST_F(SessionTest, PlaybackAdvancesAndStopsAtTheEnd) {
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings_);
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlay), &settings_);
  EXPECT_TRUE(settings_.playing);
  const int n = session_.num_frames(settings_);
  for (int i = 0; i < n + 5; ++i) session_.Tick(&settings_);
  EXPECT_FALSE(settings_.playing);
  EXPECT_EQ(settings_.frame, n - 1);
}

TEST_F(SessionTest, JointSliderMovesTheRobotAndDropsThePlan) {
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings_);
  session_.Apply(SessionCommand(SessionCommand::Kind::kSetJoint, "", 3, 0.25), &settings_);
  EXPECT_FALSE(session_.result().has_value());
  EXPECT_DOUBLE_EQ(session_.ShownQ(settings_)(3), 0.25);
  EXPECT_THROW(
      session_.Apply(SessionCommand(SessionCommand::Kind::kSetJoint, "", 99, 0.0), &settings_),
      std::invalid_argument);
  session_.Apply(SessionCommand(SessionCommand::Kind::kReset), &settings_);
  EXPECT_NE(session_.ShownQ(settings_)(3), 0.25);
}

TEST(ScriptTest, ParsesCommandsAndRejectsBadLinesWithFileAndLine) {
  const std::string path = std::filesystem::temp_directory_path() / "topoplan_script_test.txt";
  {
    std::ofstream f(path);
    f << "# comment\n\nload unwrap\nstep\nframes 3\nclick Plan\nscreenshot /tmp/x.png\nquit\n";
  }
  const std::vector<ScriptLine> lines = ParseScript(path);
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(lines[0].verb, "load");
  EXPECT_EQ(lines[0].line, 3);
  EXPECT_EQ(lines[3].args.at(0), "Plan");
  {
    std::ofstream f(path);
    f << "step\nfly away\n";
  }
  try {
    ParseScript(path);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(":2: unknown command 'fly'"), std::string::npos);
  }
  {
    std::ofstream f(path);
    f << "seek\n";
  }
  EXPECT_THROW(ParseScript(path), std::invalid_argument);
  EXPECT_THROW(ParseScript("/nonexistent/script.txt"), std::invalid_argument);
}

}  // namespace
}  // namespace app

namespace app {
namespace {

TEST(GraspReplayTest, TransfersRecordsAndStepsTheStabilityTest) {
  setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1);
  Session session;
  Settings settings;
  settings.grasp.grasp = "power_bottle";
  settings.grasp.method = "winding";
  session.Apply(SessionCommand(SessionCommand::Kind::kGraspRun), &settings);
  ASSERT_TRUE(session.grasp().has_value());
  const GraspReplay& g = *session.grasp();
  // 0.5 s closing + 6 × 2 s at 1 kHz, one frame every 20 steps (trials may stop early).
  EXPECT_GT(g.frames.size(), 100u);
  EXPECT_TRUE(g.result.stable);
  EXPECT_EQ(g.frames.front().phase, 0);
  EXPECT_TRUE(settings.grasp.active);
  EXPECT_EQ(session.GraspGravity(0).norm(), 0.0);  // gravity off while closing
  session.Apply(SessionCommand(SessionCommand::Kind::kGraspStep, "", 0, 60.0), &settings);
  EXPECT_EQ(settings.grasp.frame, 60);
  EXPECT_NEAR(session.GraspGravity(settings.grasp.frame).norm(), 9.81, 1e-9);
  session.Apply(SessionCommand(SessionCommand::Kind::kGraspStep, "", 0, 1e6), &settings);
  EXPECT_EQ(settings.grasp.frame, static_cast<int>(g.frames.size()) - 1);
}

}  // namespace
}  // namespace app
