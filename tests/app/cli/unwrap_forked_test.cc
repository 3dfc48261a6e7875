// The demo's Fig. 4.5 sweep in forked worker processes (app/cli/unwrap_forked.h) gives the same
// runs, in the same order, and the same summary as one process (measured times aside).
#include "app/cli/unwrap_forked.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "base/assets.h"
#include "planning/motion/report.h"

namespace app {
namespace {

namespace fs = std::filesystem;

// The result without its measured times (the only fields that differ from run to run).
planning::UnwrapBenchmarkResult WithoutTimes(planning::UnwrapBenchmarkResult r) {
  for (planning::UnwrapRun &run : r.runs) {
    run.report.time_s = run.report.cpu_time_s = run.report.setup_time_s = 0.0;
    run.report.goal_sampler_cpu_time_s = 0.0;
  }
  return r;
}

TEST(UnwrapForked, WorkersGiveTheSameRunsAndSummaryAsOneProcess) {
  planning::UnwrapBenchmarkOptions options;
  options.scenario_path = base::ResolveScenarioPath("unwrap");
  options.search_roots = {base::AssetRoot()};
  options.angles_deg = {0.0, 180.0, 90.0};  // not sorted: the result keeps the given order
  options.planners = {planning::Planner::kAico, planning::Planner::kBiRrt};
  options.seeds = 2;
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "unwrap_forked";
  UnwrapRunOptions run;
  run.workers = 2;
  run.scratch_dir = (dir / "scratch").string();
  const UnwrapForkedResult two = RunUnwrapBenchmarkInProcesses(options, run);
  EXPECT_FALSE(fs::exists(dir / "scratch"));
  run.workers = 1;
  const UnwrapForkedResult one = RunUnwrapBenchmarkInProcesses(options, run);
  ASSERT_EQ(two.exit_code, 0);
  ASSERT_EQ(one.exit_code, 0);
  ASSERT_EQ(two.result.runs.size(), 3u * 2u * 2u);
  EXPECT_EQ(two.result.angles_deg, options.angles_deg);
  EXPECT_EQ(planning::UnwrapCsv(WithoutTimes(one.result)),
            planning::UnwrapCsv(WithoutTimes(two.result)));
  for (size_t i = 0; i < one.result.runs.size(); ++i) {
    const planning::PlanReport &a = one.result.runs[i].report, &b = two.result.runs[i].report;
    EXPECT_EQ(a.cost_history, b.cost_history) << i;
    EXPECT_EQ(a.failure_detail, b.failure_detail) << i;
    EXPECT_EQ(a.final_writhe_total, b.final_writhe_total) << i;
    EXPECT_EQ(a.counts.pair_tests(), b.counts.pair_tests()) << i;
  }
  ASSERT_EQ(one.result.summary.size(), two.result.summary.size());
  for (size_t i = 0; i < one.result.summary.size(); ++i) {
    const planning::UnwrapCell &a = one.result.summary[i], &b = two.result.summary[i];
    EXPECT_EQ(a.angle_deg, b.angle_deg);
    EXPECT_EQ(a.planner, b.planner);
    EXPECT_EQ(a.successes, b.successes);
    EXPECT_TRUE(a.mean_checks == b.mean_checks ||
                (std::isnan(a.mean_checks) && std::isnan(b.mean_checks)));
  }
}

}  // namespace
}  // namespace app
