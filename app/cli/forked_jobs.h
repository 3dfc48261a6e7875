// Independent pieces of work run in forked child processes, a bounded number at a time (the demo's
// stages on several cores). A child is a copy of the calling process (fork without exec): it sees
// the caller's memory as it was when the job started, runs the job's function, and exits with its
// return value; nothing it changes in memory comes back, so a job hands its results over in files.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace app {

struct ForkedJob {
  std::string name;          // for messages
  std::function<int()> run;  // runs in the child; returns its exit code (0..255)
  // The child's stdout and stderr go to this file (created or truncated); empty: inherited.
  std::string log_path;
};

struct ForkedJobResult {
  bool started = false;  // false: skipped because the run was stopped before its turn
  int exit_code = 0;     // the child's exit code; 128 + N when signal N ended it
  double wall_s = 0.0;   // from fork to exit [s]
  double cpu_s = 0.0;    // user + system CPU of the child and the processes it waited for [s]
};

struct ForkedJobsOptions {
  int workers = 2;  // children running at the same time, >= 1
  // Called in the parent when job i starts and when it has ended (in the order they end).
  std::function<void(size_t i)> on_start;
  std::function<void(size_t i, const ForkedJobResult& result)> on_done;
  // Polled by the parent about every 50 ms; once it returns true no further job starts and the
  // running children get SIGTERM (once); their exit codes are still collected. Each child runs in
  // a process group of its own, so a terminal's Ctrl-C reaches only the parent, which stops the
  // children this way.
  std::function<bool()> should_stop;
};

// A counter shared by this process and the children it forks while the counter lives (anonymous
// shared memory, a lock-free atomic): jobs that each take the next piece of work from it balance
// themselves over the workers. Throws std::runtime_error when the memory cannot be mapped.
class SharedCounter {
 public:
  SharedCounter();
  ~SharedCounter();
  SharedCounter(const SharedCounter&) = delete;
  SharedCounter& operator=(const SharedCounter&) = delete;

  size_t Next();  // 0, 1, 2, ... over all processes, each value once

 private:
  void* memory_ = nullptr;
};

// Runs every job in `jobs` order, at most options.workers at a time, and waits for all of them;
// results[i] belongs to jobs[i]. Only call from a single-threaded process (fork copies only the
// calling thread); stdio is flushed before each fork. A child's exception escaping `run` ends it
// with exit code 3 (message on its stderr). Throws std::invalid_argument for workers < 1 and
// std::runtime_error when fork fails.
std::vector<ForkedJobResult> RunForkedJobs(const std::vector<ForkedJob>& jobs,
                                           const ForkedJobsOptions& options);

}  // namespace app
