// The Fig. 4.5 sweep (planning::RunUnwrapBenchmark) spread over forked worker processes: the
// demo's benchmark stage on several cores. Each worker claims the next angle from a counter the
// workers share (the largest angles first: their failing runs spend the whole budget) and hands
// the runs of that angle back as bytes in a scratch file.
#pragma once

#include <functional>
#include <string>

#include "planning/motion/unwrap_benchmark.h"

namespace app {

struct UnwrapRunOptions {
  // Processes at a time: 1 runs RunUnwrapBenchmark in this process; > 1 forks that many
  // workers (only from a single-threaded process).
  int workers = 1;
  std::string scratch_dir;  // workers > 1: created, removed before returning
  // Polled by the parent every 50 ms; once true, the running workers get SIGTERM (a worker's
  // options.progress may end its run, as in one process).
  std::function<bool()> should_stop;
};

struct UnwrapForkedResult {
  planning::UnwrapBenchmarkResult result;  // every angle's runs; see exit_code
  int exit_code = 0;  // the worst exit code of a worker; non-zero: some angle is missing
};

// RunUnwrapBenchmark(options) one angle per job: the same runs (timings aside: time_s,
// cpu_time_s, setup_time_s are measured in the worker) in the same order, and the same summary.
// options.progress runs in the workers, with the counts of the worker's angle.
UnwrapForkedResult RunUnwrapBenchmarkInProcesses(const planning::UnwrapBenchmarkOptions& options,
                                                 const UnwrapRunOptions& run);

}  // namespace app
