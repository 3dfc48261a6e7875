#include "app/viewer/worker.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <exception>
#include <utility>

namespace app {

Worker::~Worker() {
  Cancel();
  Wait(/*join_parked=*/true);
}

void Worker::StartLocked(Job job) {
  name_ = std::move(job.name);
  budget_ = job.budget;
  units_ = 0;
  running_ = true;
  finished_ = parked_ = cancel_ = false;
  error_.clear();
  thread_ = std::thread([this, run = std::move(job.run)] {
    if (nice_ > 0) {  // this thread only (best effort: raising one's niceness is always allowed)
      const id_t tid = static_cast<id_t>(syscall(SYS_gettid));
      setpriority(PRIO_PROCESS, tid, getpriority(PRIO_PROCESS, tid) + nice_);
    }
    std::string error;
    try {
      run(*this);
    } catch (const Cancelled&) {
    } catch (const std::exception& e) {
      error = e.what();
    } catch (...) {
      error = "unknown error";
    }
    std::lock_guard<std::mutex> lock(mutex_);
    error_ = error;
    finished_ = true;
    parked_ = false;
    cv_.notify_all();
  });
}

void Worker::Submit(Job job) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (running_) {
    queue_.push_back(std::move(job));
  } else {
    StartLocked(std::move(job));
  }
}

bool Worker::Collect() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!running_ || !finished_) return false;
  std::thread done = std::move(thread_);
  running_ = false;
  last_error_ = error_;
  last_cancelled_ = cancel_;
  name_.clear();
  lock.unlock();
  done.join();  // the job has returned: only the thread's exit remains
  lock.lock();
  if (!running_ && !queue_.empty()) {
    Job next = std::move(queue_.front());
    queue_.pop_front();
    StartLocked(std::move(next));
  }
  return true;
}

void Worker::Cancel() {
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.clear();
  if (running_) cancel_ = true;
  parked_ = false;
  cv_.notify_all();
}

void Worker::Wait(bool join_parked) {
  for (;;) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!running_) return;
    cv_.wait(lock, [&] { return finished_ || (parked_ && !cancel_); });
    if (!finished_) {
      if (!join_parked) return;
      cancel_ = true;
      cv_.notify_all();
      cv_.wait(lock, [&] { return finished_; });
    }
    lock.unlock();
    Collect();
  }
}

bool Worker::AddBudget(long n) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!running_ || finished_ || cancel_) return false;
  if (n < 0) {
    budget_ = -1;
  } else if (budget_ >= 0) {
    budget_ += n;
  }
  parked_ = false;  // the job resumes (it parks again when the new budget is used up)
  cv_.notify_all();
  return true;
}

bool Worker::busy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return running_ || !queue_.empty();
}

bool Worker::computing() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return running_ && !finished_ && !parked_;
}

bool Worker::parked() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return running_ && parked_ && !cancel_;
}

std::string Worker::job_name() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return running_ ? name_ : std::string();
}

long Worker::units() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return units_;
}

std::string Worker::last_error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_error_;
}

bool Worker::last_cancelled() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_cancelled_;
}

void Worker::Checkpoint() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (cancel_) throw Cancelled{};
  ++units_;
  while (!cancel_ && budget_ >= 0 && units_ >= budget_) {
    parked_ = true;
    cv_.notify_all();
    cv_.wait(lock);
  }
  parked_ = false;
  if (cancel_) throw Cancelled{};
}

bool Worker::AtBudget() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return budget_ >= 0 && units_ + 1 >= budget_;
}

void Worker::ThrowIfCancelled() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (cancel_) throw Cancelled{};
}

}  // namespace app
