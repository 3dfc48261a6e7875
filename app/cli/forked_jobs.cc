#include "app/cli/forked_jobs.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <thread>

#include "base/str_cat.h"

namespace app {
namespace {

using Clock = std::chrono::steady_clock;

// In the child: redirect stdout/stderr, run, flush, exit without unwinding the parent's stack
// (its destructors, e.g. an output folder's clean-up, belong to the parent).
[[noreturn]] void RunChild(const ForkedJob& job) {
  int rc = 3;
  // A process group of its own: a terminal's Ctrl-C reaches only the parent, which then sends
  // each child exactly one SIGTERM (a second signal would end a command abruptly).
  ::setpgid(0, 0);
  if (!job.log_path.empty()) {
    const int fd = ::open(job.log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || ::dup2(fd, STDOUT_FILENO) < 0 || ::dup2(fd, STDERR_FILENO) < 0) {
      std::fprintf(stderr, "topoplan: %s: cannot write %s: %s\n", job.name.c_str(),
                   job.log_path.c_str(), std::strerror(errno));
      std::fflush(stderr);
      ::_exit(3);
    }
    if (fd > STDERR_FILENO) ::close(fd);
    // One log for both streams: line-buffered stdout keeps the lines in the order printed.
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
  }
  try {
    rc = job.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "topoplan: %s: error: %s\n", job.name.c_str(), e.what());
  } catch (...) {
    std::fprintf(stderr, "topoplan: %s: unknown error\n", job.name.c_str());
  }
  std::fflush(nullptr);
  ::_exit(rc & 0xff);
}

double Seconds(const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * t.tv_usec; }

}  // namespace

SharedCounter::SharedCounter() {
  static_assert(std::atomic<size_t>::is_always_lock_free);
  memory_ = ::mmap(nullptr, sizeof(std::atomic<size_t>), PROT_READ | PROT_WRITE,
                   MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (memory_ == MAP_FAILED) {
    throw std::runtime_error(base::StrCat("cannot map shared memory: ", std::strerror(errno)));
  }
  new (memory_) std::atomic<size_t>(0);
}

SharedCounter::~SharedCounter() { ::munmap(memory_, sizeof(std::atomic<size_t>)); }

size_t SharedCounter::Next() { return static_cast<std::atomic<size_t>*>(memory_)->fetch_add(1); }

std::vector<ForkedJobResult> RunForkedJobs(const std::vector<ForkedJob>& jobs,
                                           const ForkedJobsOptions& options) {
  if (options.workers < 1) throw std::invalid_argument("forked jobs: workers must be >= 1");
  std::vector<ForkedJobResult> results(jobs.size());
  struct Running {
    size_t job;
    pid_t pid;
    Clock::time_point start;
  };
  std::vector<Running> running;
  size_t next = 0;
  bool stopped = false;
  while ((!stopped && next < jobs.size()) || !running.empty()) {
    if (!stopped && options.should_stop && options.should_stop()) {
      stopped = true;
      for (const Running& r : running) ::kill(r.pid, SIGTERM);
    }
    while (!stopped && next < jobs.size() && static_cast<int>(running.size()) < options.workers) {
      const size_t i = next++;
      if (options.on_start) options.on_start(i);
      std::fflush(nullptr);  // nothing buffered may be written twice
      const pid_t pid = ::fork();
      if (pid < 0) {
        for (const Running& r : running) ::kill(r.pid, SIGTERM);
        for (const Running& r : running) ::waitpid(r.pid, nullptr, 0);
        throw std::runtime_error(
            base::StrCat("cannot start ", jobs[i].name, ": fork failed: ", std::strerror(errno)));
      }
      if (pid == 0) RunChild(jobs[i]);
      ::setpgid(pid, pid);  // as the child does: whichever runs first (no window for a Ctrl-C)
      results[i].started = true;
      running.push_back({i, pid, Clock::now()});
    }
    bool reaped = false;
    for (size_t k = 0; k < running.size();) {
      int status = 0;
      rusage usage{};
      const pid_t got = ::wait4(running[k].pid, &status, WNOHANG, &usage);
      if (got == 0 || (got < 0 && errno == EINTR)) {
        ++k;
        continue;
      }
      ForkedJobResult& r = results[running[k].job];
      r.wall_s = std::chrono::duration<double>(Clock::now() - running[k].start).count();
      if (got == running[k].pid) {
        r.cpu_s = Seconds(usage.ru_utime) + Seconds(usage.ru_stime);
        r.exit_code = WIFEXITED(status)     ? WEXITSTATUS(status)
                      : WIFSIGNALED(status) ? 128 + WTERMSIG(status)
                                            : 3;
      } else {
        r.exit_code = 3;  // lost (not our child any more): an environment error
      }
      const size_t job = running[k].job;
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
      reaped = true;
      if (options.on_done) options.on_done(job, r);
    }
    if (!reaped && !running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return results;
}

}  // namespace app
