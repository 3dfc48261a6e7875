// The demo's grasp trials in forked worker processes (app/cli/grasp_forked.h) give the same result
// and the same frame files as one process; a trial survives its trip through bytes
// (planning/physics/grasp_trial_codec.h).
#include "app/cli/grasp_forked.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "planning/physics/grasp_report.h"
#include "planning/physics/grasp_trial_codec.h"

namespace app {
namespace {

namespace fs = std::filesystem;
namespace phys = planning::physics;

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Every file under `root` by its relative path, with its bytes.
std::map<std::string, std::string> Files(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    files[fs::relative(e.path(), root).string()] =
        std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  return files;
}

TEST(GraspForked, WorkersGiveTheSameResultAndFramesAsOneProcess) {
  const planning::GraspInputs in =
      planning::LoadGraspInputs(planning::SelectGraspFiles("lateral_pinch_box"));
  const std::vector<planning::TransferMethod> methods = {planning::TransferMethod::kWinding,
                                                         planning::TransferMethod::kJointMapping,
                                                         planning::TransferMethod::kHuman};
  const phys::GraspTrialsOptions options;
  const fs::path dir = TempDir("grasp_forked");
  GraspRunOptions run;
  run.frames = true;
  // The workers first: this process has no GL context (and no llvmpipe threads) yet.
  run.workers = 2;
  run.out_dir = (dir / "two").string();
  run.scratch_dir = (dir / "scratch").string();
  const GraspRunResult two = RunGraspTrialsInProcesses(in, methods, options, run);
  EXPECT_FALSE(fs::exists(dir / "scratch"));
  // Frames of the winding trial only (the demo's default), also in workers.
  run.frame_methods = {planning::TransferMethod::kWinding};
  run.out_dir = (dir / "winding_only").string();
  const GraspRunResult some = RunGraspTrialsInProcesses(in, methods, options, run);
  run.frame_methods.clear();
  run.workers = 1;
  run.out_dir = (dir / "one").string();
  const GraspRunResult one = RunGraspTrialsInProcesses(in, methods, options, run);
  ASSERT_EQ(one.exit_code, 0);
  ASSERT_EQ(two.exit_code, 0);
  ASSERT_TRUE(two.trials.complete);
  ASSERT_EQ(two.trials.trials.size(), 1u);
  EXPECT_EQ(phys::GraspReportJson(one.trials).dump(1), phys::GraspReportJson(two.trials).dump(1));
  EXPECT_EQ(phys::GraspSummaryMarkdown(one.trials), phys::GraspSummaryMarkdown(two.trials));
  const auto a = Files(dir / "one"), b = Files(dir / "two");
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(a.size(), 30u);  // transfer and stability frames of three trials
  for (const auto& [name, bytes] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    EXPECT_TRUE(b.at(name) == bytes) << name << " differs";
  }
  // The winding-only run: the same result, one trial's folder with the same files.
  ASSERT_EQ(some.exit_code, 0);
  EXPECT_EQ(phys::GraspReportJson(one.trials).dump(1), phys::GraspReportJson(some.trials).dump(1));
  std::vector<std::string> folders;
  for (const auto& e : fs::directory_iterator(dir / "winding_only" / "frames")) {
    folders.push_back(e.path().filename().string());
  }
  EXPECT_EQ(folders, std::vector<std::string>{"lateral_pinch_box_winding"});
  const auto c = Files(dir / "winding_only");
  size_t winding_files = 0;
  for (const auto& [name, bytes] : a) {
    if (name.rfind("frames/lateral_pinch_box_winding/", 0) != 0) continue;
    ++winding_files;
    ASSERT_TRUE(c.count(name)) << name;
    EXPECT_TRUE(c.at(name) == bytes) << name << " differs";
  }
  EXPECT_EQ(c.size(), winding_files);
  EXPECT_TRUE(c.count("frames/lateral_pinch_box_winding/transfer/side_by_side.png"));
  // Bytes and back: every field the reports read, bit for bit.
  for (const phys::GraspTrial& t : one.trials.trials[0]) {
    const std::string bytes = phys::EncodeGraspTrial(t);
    EXPECT_EQ(phys::EncodeGraspTrial(phys::DecodeGraspTrial(bytes)), bytes);
    EXPECT_THROW(phys::DecodeGraspTrial(bytes.substr(0, bytes.size() - 1)), std::runtime_error);
    EXPECT_THROW(phys::DecodeGraspTrial(bytes + "x"), std::runtime_error);
  }
}

}  // namespace
}  // namespace app
