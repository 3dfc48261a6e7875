// Small input/output helpers for commands: atomic file writes, output folders written as a whole,
// checked flag parsing, interrupts and time limits.
#pragma once

#include "base/numbers.h"  // ParseNumberList, ParseFiniteDouble
#include "render/figure.h"

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace app {

// A progress line on stderr (printf format): on a terminal it overwrites the previous one ("\r"),
// in a log file or pipe it is a line of its own. EndProgress() ends a terminal's progress line
// (prints nothing otherwise).
void Progress(const char* format, ...) __attribute__((format(printf, 1, 2)));
void EndProgress();

// Writes `contents` to `path` atomically: a temporary file in the same folder, then rename, so a
// failure never leaves a half-written output. Creates missing parent folders. Throws
// std::runtime_error naming the path on failure.
void WriteFileAtomic(const std::string& path, const std::string& contents);


// CLI11 check of a number flag: the text is a finite number (as ParseNumberList) in [lo, hi].
// "--start-wrap nan" or "--threshold 2" fail at parsing with exit code 2.
CLI::Validator FiniteIn(double lo, double hi);

// Checks, before any computation, that `dir` can be used as an output folder: not empty, and
// either a writable folder or creatable (its nearest existing ancestor is a writable folder).
// Throws std::invalid_argument naming `flag` otherwise.
void CheckOutputDir(const std::string& dir, const std::string& flag);

// Checks, before any computation, that `path` can be written as an output file: not empty, not a
// folder, and its folder usable (CheckOutputDir). Throws std::invalid_argument naming `flag`.
void CheckOutputFile(const std::string& path, const std::string& flag);

// Largest writhe matrix computed from chain files: (N_A − 1)(N_B − 1) segment pairs, 8 bytes each.
inline constexpr long long kMaxWrithePairs = 25'000'000;  // 200 MB

// Throws std::invalid_argument, before the computation, when the writhe matrix of chains of
// `rows` and `cols` points would exceed kMaxWrithePairs (the message gives the memory needed).
void CheckWrithePairs(long long rows_points, long long cols_points);

// An output folder whose files appear together or not at all. The constructor checks `dir`
// (CheckOutputDir) and creates an empty staging folder next to it ("<dir>.partial-<pid>"); the
// run writes into staging(). Commit() moves every staged entry into `dir` (created if missing;
// entries of the same name are replaced) and removes the staging folder. Without Commit (an
// exception, an interrupt) the destructor removes the staging folder and `dir` is untouched.
class OutputDir {
 public:
  OutputDir(const std::string& dir, const std::string& flag);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  const std::string& dir() const { return dir_; }
  const std::string& staging() const { return staging_; }
  void Commit();

 private:
  std::string dir_, staging_;
  bool committed_ = false;
};

// Thrown by StopCheck::Poll when the run must stop; `timeout` tells which reason.
struct StopRequested : std::runtime_error {
  explicit StopRequested(bool is_timeout)
      : std::runtime_error(is_timeout ? "time limit reached" : "interrupted"),
        timeout(is_timeout) {}
  bool timeout;
};

// Interrupts (SIGINT, SIGTERM) and the --timeout limit of a long command. While a StopCheck
// lives, the first SIGINT/SIGTERM only sets a flag (a second one terminates as usual); Poll(),
// called between units of work (an AICO sweep, a benchmark run, a grasp trial), throws
// StopRequested when a signal arrived or the time limit passed. StopChecks nest (a command run by
// the demo): the innermost sees the earliest deadline of all. Exit codes: 1 for a timeout
// (`"status": "timeout"`), 130 for an interrupt.
class StopCheck {
 public:
  // `timeout_s` <= 0: no time limit.
  explicit StopCheck(double timeout_s);
  ~StopCheck();
  StopCheck(const StopCheck&) = delete;
  StopCheck& operator=(const StopCheck&) = delete;

  void Poll() const;
  bool Stopped() const;

 private:
  std::optional<std::chrono::steady_clock::time_point> previous_deadline_;
};

// --timeout SECONDS on a command (0 = none, at most 1e6 s).
void AddTimeoutFlag(CLI::App* command, double* seconds);

// --formats LIST on a command that writes several figures: "png,svg,pdf" or a subset (default
// png). The parsed list is checked at parse time (exit 2 for an unknown name).
void AddFormatsFlag(CLI::App* command, std::vector<render::FigureFormat>* formats);

}  // namespace app
