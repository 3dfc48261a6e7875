// Small input/output helpers for commands: atomic file writes, output folders written as a whole,
// checked flag parsing, interrupts and time limits.
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/file_write.h"  // WriteFileAtomic, CheckOutputFile, CheckOutputDir
#include "base/numbers.h"     // ParseNumberList, ParseFiniteDouble

namespace app {

// A progress line on stderr (printf format): on a terminal it overwrites the previous one ("\r"),
// in a log file or pipe it is a line of its own. EndProgress() ends a terminal's progress line
// (prints nothing otherwise).
void Progress(const char* format, ...) __attribute__((format(printf, 1, 2)));
void EndProgress();

// How much a command says on stdout/stderr besides its results and errors: -q/--quiet (kQuiet:
// no progress, no "wrote ..." notes), default (kNormal), -v/--verbose (kVerbose: also Detail()
// lines). Errors and the results a command exists to print (tables, --json) are never silenced.
enum class Verbosity { kQuiet, kNormal, kVerbose };
void SetVerbosity(Verbosity v);
Verbosity GetVerbosity();
// The command line of this process ("topoplan plan unwrap -o out"), set once by the outermost
// RunCommandLine (the demo's commands keep the demo's), shell-quoted where needed.
void SetCommandLine(int argc, char** argv);
const std::string& CommandLine();

// {"version", "commit", "command"}: where a report came from (no clock time, so that the same
// inputs give the same file).
nlohmann::json ProvenanceJson();

// --strict: every warning is an error (exit 2).
void SetStrict(bool strict);
bool Strict();
// Prints each warning on stderr ("topoplan: warning: ..."); with --strict throws
// std::invalid_argument with the first one instead.
void ReportWarnings(const std::vector<std::string>& warnings);
// Prints each note on stderr ("topoplan: note: ...", so --json output stays clean); nothing with
// -q. For what a command chose on the user's behalf (a default pose, no SRDF found).
void ReportNotes(const std::vector<std::string>& notes);

// A note for the user on stdout ("wrote out/report.json"), one line; silent with -q.
void Note(const char* format, ...) __attribute__((format(printf, 1, 2)));
// A detail on stderr, one line; only with -v.
void Detail(const char* format, ...) __attribute__((format(printf, 1, 2)));

// CLI11 check of a number flag: the text is a finite number (as ParseNumberList) in [lo, hi].
// "--start-wrap nan" or "--threshold 2" fail at parsing with exit code 2.
CLI::Validator FiniteIn(double lo, double hi);

// CLI11 check of a flag whose value must not be empty: `--budget ""` fails at parsing with exit
// code 2 ("--budget: empty value; leave the flag out for its default") instead of silently meaning
// the default.
CLI::Validator NonEmpty();

// Largest writhe matrix computed from chain files: (N_A − 1)(N_B − 1) segment pairs, 8 bytes each.
inline constexpr long long kMaxWrithePairs = 25'000'000;  // 200 MB

// Throws std::invalid_argument, before the computation, when the writhe matrix of chains of
// `rows` and `cols` points would exceed kMaxWrithePairs (the message gives the memory needed).
void CheckWrithePairs(long long rows_points, long long cols_points);

// An output folder written as a whole by one command (its staging area is a hidden folder inside
// it, on the same file system). The constructor checks, before any work, that `dir` is absent
// (then created), empty, or a folder of topoplan's outputs (it holds the manifest
// `.topoplan-outputs.json`), and not one of `inputs`; a folder with other files is refused
// (std::invalid_argument naming `flag`, exit 2). Staging folders of processes that were killed
// are removed. The run writes into staging(). Commit() replaces what the previous run of the same
// `command` wrote there ("plan", "bench unwrap": its entries not written again are removed, so no
// stale frames stay behind), moves every staged entry into `dir` and records them in the
// manifest. Commit(false) (an interrupted run keeping its partial rows) adds the staged entries
// and leaves the earlier complete outputs of the same command in place. Without Commit (an
// exception, an interrupt) staging is removed and `dir` is as it was (a folder this run created is
// removed again).
class OutputDir {
 public:
  OutputDir(const std::string& dir, const std::string& flag, const std::string& command,
            const std::vector<std::string>& inputs = {});
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  const std::string& dir() const { return dir_; }
  const std::string& staging() const { return staging_; }
  void Commit(bool replace_previous = true);
  // DIR/.topoplan-journal-<name>: where a run keeps the journal of its finished work
  // (base::LineJournal) so that a hard-killed run can resume. It lives in `dir` itself (not in
  // staging, which a later run removes), is never moved by Commit, and the constructor accepts a
  // folder holding one; the run deletes it once its outputs are committed.
  std::string JournalPath(const std::string& name) const;

 private:
  std::string dir_, staging_, command_;
  bool created_ = false;
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

// Progress and Ctrl-C for a streamed computation over segment pairs (topology::
// WritheStreamOptions::progress): the returned callback calls stop.Poll() (so an interrupt stops
// the work within one unit, exit 130) and, once the run has lasted a second, prints at most one
// Progress() line per second: "<label>: 42% of 1.0e+10 segment pairs, 12 s". Call EndProgress()
// afterwards.
std::function<void(long long, long long)> PairProgress(const std::string& label,
                                                       const StopCheck& stop);
// --threads N of a streamed writhe computation (0 = all cores, at most 256).
void AddStreamThreadsFlag(CLI::App* command, int* threads);

// An integer flag in [lo, hi]: decimal digits only ("010" is 10, never octal; "", "0x10", "1.5"
// and "12abc" are refused at parsing, exit 2), its help type shown as "INT in [lo, hi]".
CLI::Option* IntIn(CLI::Option* option, long long lo, long long hi);
// Makes every integer option of `app` and its subcommands strictly decimal (as IntIn, without a
// range); called once the command line is built.
void StrictIntegerOptions(CLI::App* app);

// An old spelling of a flag, kept working for one release: a hidden option storing into the same
// variable as `new_flag` (with `configure` applied, e.g. the same checks) that prints
// "topoplan: warning: OLD is deprecated; use NEW" when given. Returns the alias.
template <typename T>
CLI::Option* AddDeprecatedAlias(CLI::App* cmd, const std::string& old_flag,
                                const std::string& new_flag, T* variable) {
  CLI::Option* o = cmd->add_option(old_flag, *variable, "deprecated: use " + new_flag);
  o->group("");  // not in --help
  o->check(CLI::Validator(
      [old_flag, new_flag](std::string&) -> std::string {
        std::fprintf(stderr, "topoplan: warning: %s is deprecated; use %s\n", old_flag.c_str(),
                     new_flag.c_str());
        return "";
      },
      ""));
  return o;
}

// --timeout SECONDS on a command (0, the default: no time limit; at most 1e6 s).
void AddTimeoutFlag(CLI::App* command, double* seconds);

}  // namespace app
