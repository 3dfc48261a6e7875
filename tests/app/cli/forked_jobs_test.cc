// Jobs in forked processes (app/cli/forked_jobs.h): results by job, exit codes, logs, CPU time,
// the bound on running children, and stopping.
#include "app/cli/forked_jobs.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace app {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string Slurp(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(ForkedJobsTest, ResultsBelongToTheirJobsWithLogsAndExitCodes) {
  const fs::path dir = TempDir("forked_jobs_results");
  std::vector<ForkedJob> jobs;
  for (int i = 0; i < 5; ++i) {
    jobs.push_back({"job" + std::to_string(i),
                    [i] {
                      std::printf("out %d\n", i);
                      std::fprintf(stderr, "err %d\n", i);
                      // Later jobs end first: results must still be by job, not by end.
                      std::this_thread::sleep_for(std::chrono::milliseconds(60 * (5 - i)));
                      return i == 3 ? 2 : 0;
                    },
                    (dir / ("job" + std::to_string(i) + ".log")).string()});
  }
  ForkedJobsOptions o;
  o.workers = 2;
  std::vector<size_t> ended;
  o.on_done = [&](size_t i, const ForkedJobResult&) { ended.push_back(i); };
  const std::vector<ForkedJobResult> r = RunForkedJobs(jobs, o);
  ASSERT_EQ(r.size(), 5u);
  ASSERT_EQ(ended.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(r[i].started);
    EXPECT_EQ(r[i].exit_code, i == 3 ? 2 : 0) << i;
    EXPECT_GT(r[i].wall_s, 0.0);
    EXPECT_GE(r[i].cpu_s, 0.0);
    EXPECT_EQ(Slurp(dir / ("job" + std::to_string(i) + ".log")),
              "out " + std::to_string(i) + "\nerr " + std::to_string(i) + "\n");
  }
}

TEST(ForkedJobsTest, AtMostWorkersRunAtOnce) {
  const fs::path dir = TempDir("forked_jobs_workers");
  // Each child marks itself running with a file, counts the marks, and removes its own.
  std::vector<ForkedJob> jobs;
  for (int i = 0; i < 6; ++i) {
    jobs.push_back({"j",
                    [dir, i] {
                      const fs::path mine = dir / ("running" + std::to_string(i));
                      std::ofstream(mine) << i;
                      std::this_thread::sleep_for(std::chrono::milliseconds(150));
                      int running = 0;
                      for (const auto& e : fs::directory_iterator(dir)) {
                        running += e.path().filename().string().rfind("running", 0) == 0;
                      }
                      fs::remove(mine);
                      return running;
                    },
                    ""});
  }
  ForkedJobsOptions o;
  o.workers = 2;
  for (const ForkedJobResult& r : RunForkedJobs(jobs, o)) {
    EXPECT_GE(r.exit_code, 1);
    EXPECT_LE(r.exit_code, 2);
  }
}

TEST(ForkedJobsTest, ChildMemoryChangesStayInTheChild) {
  int value = 1;
  std::vector<ForkedJob> jobs = {{"j",
                                  [&value] {
                                    value = 42;
                                    return value;
                                  },
                                  ""}};
  const std::vector<ForkedJobResult> r = RunForkedJobs(jobs, ForkedJobsOptions{});
  EXPECT_EQ(r[0].exit_code, 42);
  EXPECT_EQ(value, 1);
}

TEST(ForkedJobsTest, ExceptionsAndSignalsBecomeExitCodes) {
  std::vector<ForkedJob> jobs = {{"throws", []() -> int { throw std::runtime_error("boom"); }, ""},
                                 {"killed",
                                  [] {
                                    ::kill(::getpid(), SIGKILL);
                                    return 0;
                                  },
                                  ""}};
  const std::vector<ForkedJobResult> r = RunForkedJobs(jobs, ForkedJobsOptions{});
  EXPECT_EQ(r[0].exit_code, 3);
  EXPECT_EQ(r[1].exit_code, 128 + SIGKILL);
}

TEST(ForkedJobsTest, StopSkipsUnstartedJobsAndTerminatesRunningOnes) {
  std::vector<ForkedJob> jobs;
  for (int i = 0; i < 4; ++i) {
    jobs.push_back({"sleeper",
                    [] {
                      std::this_thread::sleep_for(std::chrono::seconds(30));
                      return 0;
                    },
                    ""});
  }
  ForkedJobsOptions o;
  o.workers = 2;
  const auto t0 = std::chrono::steady_clock::now();
  o.should_stop = [&] {
    return std::chrono::steady_clock::now() - t0 > std::chrono::milliseconds(300);
  };
  const std::vector<ForkedJobResult> r = RunForkedJobs(jobs, o);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 20.0);
  EXPECT_TRUE(r[0].started);
  EXPECT_TRUE(r[1].started);
  EXPECT_FALSE(r[2].started);
  EXPECT_FALSE(r[3].started);
  EXPECT_EQ(r[0].exit_code, 128 + SIGTERM);
}

TEST(ForkedJobsTest, RefusesNoWorkers) {
  ForkedJobsOptions o;
  o.workers = 0;
  EXPECT_THROW(RunForkedJobs({}, o), std::invalid_argument);
}

TEST(ForkedJobsTest, SharedCounterGivesEachValueToOneChild) {
  const fs::path dir = TempDir("forked_jobs_counter");
  SharedCounter next;
  std::vector<ForkedJob> jobs;
  for (int i = 0; i < 3; ++i) {
    const fs::path out = dir / ("taken" + std::to_string(i));
    jobs.push_back({"job" + std::to_string(i),
                    [&next, out] {
                      std::ofstream f(out);
                      for (size_t k = next.Next(); k < 200; k = next.Next()) f << k << "\n";
                      return 0;
                    },
                    ""});
  }
  ForkedJobsOptions options;
  options.workers = 3;
  for (const ForkedJobResult& r : RunForkedJobs(jobs, options)) EXPECT_EQ(r.exit_code, 0);
  std::vector<int> seen(200, 0);
  for (int i = 0; i < 3; ++i) {
    std::ifstream f(dir / ("taken" + std::to_string(i)));
    for (size_t k; f >> k;) {
      ASSERT_LT(k, 200u);
      ++seen[k];
    }
  }
  for (size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << k;
  EXPECT_GE(next.Next(), 203u);  // each child took one value past the end
}

}  // namespace
}  // namespace app
