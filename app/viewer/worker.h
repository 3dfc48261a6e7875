// app::Worker: runs the viewer's long jobs (plans, ODE simulations, re-plans) off the draw thread.
// One job at a time on its own std::thread, later jobs wait in a FIFO; the draw thread calls
// Collect() once per frame and never waits for a job unless it asks to (Wait). Jobs cooperate
// through Checkpoint(): one call per unit of work (an AICO sweep, an ODE step); it throws
// Worker::Cancelled after Cancel() and parks the job while its step budget is used up, which is
// how "step N" runs exactly N real units and then holds the solver's state until the next step.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace app {

class Worker {
 public:
  // Thrown by Checkpoint() in the job's thread once the job is cancelled; the job lets it
  // propagate (Worker catches it) after dropping its partial output.
  struct Cancelled {};
  // budget < 0: run to the end; otherwise the number of Checkpoint() calls that return before the
  // job parks (AddBudget raises it).
  struct Job {
    std::string name;
    std::function<void(Worker& worker)> run;
    long budget = -1;
  };

  // `nice` > 0 lowers the job threads' scheduling priority by that much (Linux: per-thread nice),
  // so that on a busy machine the thread drawing frames gets the CPU before a long solve.
  explicit Worker(int nice = 0) : nice_(nice) {}
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;
  // Cancels every job and joins the thread: no thread outlives the Worker.
  ~Worker();

  // Queues `job`; it starts at once when nothing runs (else when Collect() finds the running job
  // finished).
  void Submit(Job job);
  // Joins the running job's thread if the job returned, and starts the next queued job. Returns
  // true when a job finished since the last call. Never blocks on a running job.
  bool Collect();
  // Asks the running job to stop at its next Checkpoint and drops the queued jobs.
  void Cancel();
  // Blocks until the running job finished or is parked at an exhausted budget (and the queue is
  // empty), then Collect()s. With `join_parked`, a parked job is cancelled and joined as well.
  void Wait(bool join_parked = false);
  // Adds n to the running job's budget (budget < 0: unlimited); false when no job runs.
  bool AddBudget(long n);

  // True while a job's thread exists (running, parked or finished but not collected) or queued.
  bool busy() const;
  // True while a job runs (not parked, not finished).
  bool computing() const;
  bool parked() const;
  // Name of the running (or parked) job, "" when none.
  std::string job_name() const;
  // Checkpoint() calls of the running job so far.
  long units() const;
  // The last job's error message ("" when it finished or was cancelled).
  std::string last_error() const;
  // Whether the last collected job ended through Cancel().
  bool last_cancelled() const;

  // Called by the job: one unit of work is done. Parks while the budget is used up; throws
  // Cancelled after Cancel().
  void Checkpoint();
  // Called by the job: true when the next Checkpoint() will park (record what should be shown).
  bool AtBudget() const;
  // Called by the job inside a unit of work (e.g. between the physics steps of a phase): throws
  // Cancelled after Cancel(); counts nothing, never parks.
  void ThrowIfCancelled() const;

 private:
  void StartLocked(Job job);

  int nice_ = 0;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::thread thread_;
  std::deque<Job> queue_;
  std::string name_;
  long budget_ = -1, units_ = 0;
  bool running_ = false, finished_ = false, parked_ = false, cancel_ = false;
  bool last_cancelled_ = false;
  std::string error_, last_error_;
};

}  // namespace app
