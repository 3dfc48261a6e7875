// The headless viewer (same panels and renderer as the window) against golden images.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/ui/viewer.h"
#include "render/diff.h"
#include "render/image.h"

namespace app::ui {
namespace {

std::string Tmp(const std::string& name) {
  return (std::filesystem::path(TOPOPLAN_BINARY_DIR) / "viewer-test" / name).string();
}

render::Image RunScript(const std::string& name, const std::string& script_text) {
  std::filesystem::create_directories(Tmp(""));
  const std::string script = Tmp(name + ".txt");
  std::ofstream(script) << script_text;
  ViewerOptions o;
  o.scenario = "unwrap";
  o.script = script;
  o.screenshot = Tmp(name + ".png");
  o.width = 1024;
  o.height = 640;
  EXPECT_EQ(RunViewer(o), 0);
  return render::ReadPng(o.screenshot);
}

void ExpectGolden(const render::Image& image, const std::string& name) {
  const render::SnapshotResult r =
      render::CheckSnapshot(image, TOPOPLAN_SOURCE_DIR "/snapshots/viewer/" + name + ".png",
                            TOPOPLAN_BINARY_DIR "/snapshot-diff/viewer");
  EXPECT_TRUE(r.passed) << r.message;
}

class ViewerSnapshotTest : public ::testing::Test {
 protected:
  void SetUp() override { setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1); }
};

TEST_F(ViewerSnapshotTest, StartOfUnwrapWithPanels) {
  ExpectGolden(RunScript("start", "frames 2\n"), "unwrap_start");
}

TEST_F(ViewerSnapshotTest, ClickingPlanThenSeekingShowsTheUnwoundArm) {
  const render::Image planned = RunScript("planned", "click Plan\nframes 3\nseek 50\nframes 2\n");
  ExpectGolden(planned, "unwrap_planned");
  // Scripted clicks go through ImGui like the mouse: clicking "chains" changes the frame.
  const render::Image no_chains =
      RunScript("no_chains", "click Plan\nframes 3\nseek 50\nclick chains\nframes 3\n");
  EXPECT_FALSE(render::CompareImages(planned, no_chains).passed);
}

TEST_F(ViewerSnapshotTest, GraspPanelReplaysTheOdeTestStepByStep) {
  // Transfer the power grasp to the SDH, run the stability test, show 1.2 s into it (+x gravity).
  ExpectGolden(RunScript("grasp", "grasp power_bottle winding\ngrasp_step 60\nframes 2\n"),
               "grasp_power_bottle");
}

}  // namespace
}  // namespace app::ui
