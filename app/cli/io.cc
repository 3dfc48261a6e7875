#include "app/cli/io.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "base/file_read.h"
#include "base/str_cat.h"
#include "base/version.h"

namespace app {

namespace {
bool StderrIsTerminal() {
  static const bool tty = isatty(STDERR_FILENO) == 1;
  return tty;
}
}  // namespace

namespace {
Verbosity g_verbosity = Verbosity::kNormal;
}  // namespace

void SetVerbosity(Verbosity v) { g_verbosity = v; }

namespace {
bool g_strict = false;
}  // namespace

void SetStrict(bool strict) { g_strict = strict; }
bool Strict() { return g_strict; }

void ReportWarnings(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  if (g_strict) throw std::invalid_argument("--strict: " + warnings.front());
  for (const std::string& w : warnings) std::fprintf(stderr, "topoplan: warning: %s\n", w.c_str());
}

void ReportNotes(const std::vector<std::string>& notes) {
  if (g_verbosity == Verbosity::kQuiet) return;
  for (const std::string& n : notes) std::fprintf(stderr, "topoplan: note: %s\n", n.c_str());
}

namespace {
std::string g_command_line;
}  // namespace

void SetCommandLine(int argc, char** argv) {
  if (!g_command_line.empty()) return;  // the outermost command's
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i] ? argv[i] : "";
    if (i == 0) a = "topoplan";
    const bool plain = !a.empty() && a.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyz"
                                         "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_-+=.,:/@%") == std::string::npos;
    if (!plain) {
      std::string q = "'";
      for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
      a = q + "'";
    }
    g_command_line += (i ? " " : "") + a;
  }
}

const std::string& CommandLine() { return g_command_line; }

nlohmann::json ProvenanceJson() {
  return {{"version", base::Version()}, {"commit", base::Commit()}, {"command", g_command_line}};
}
Verbosity GetVerbosity() { return g_verbosity; }

void Note(const char* format, ...) {
  if (g_verbosity == Verbosity::kQuiet) return;
  va_list args;
  va_start(args, format);
  std::vprintf(format, args);
  va_end(args);
  std::fputc('\n', stdout);
}

void Detail(const char* format, ...) {
  if (g_verbosity != Verbosity::kVerbose) return;
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
  std::fputc('\n', stderr);
}

void Progress(const char* format, ...) {
  if (g_verbosity == Verbosity::kQuiet) return;
  const bool tty = StderrIsTerminal();
  char line[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof line, format, args);
  va_end(args);
  if (tty) {
    std::fprintf(stderr, "\r%s   ", line);
  } else {
    std::fprintf(stderr, "%s\n", line);
  }
}

void EndProgress() {
  if (StderrIsTerminal() && g_verbosity != Verbosity::kQuiet) std::fputc('\n', stderr);
}

namespace {

// Rewrites a decimal integer to its plain form ("+010" -> "10") for CLI11, which would read a
// leading 0 as octal; anything else is an error.
CLI::Validator DecimalInteger() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::optional<long long> v = base::ParseInteger(text);
        if (!v) return "'" + text + "' is not a whole decimal number";
        text = std::to_string(*v);
        return "";
      },
      "");
}

bool IsIntegerType(const CLI::Option* o) {
  const std::string t = o->get_type_name();
  return t.rfind("INT", 0) == 0 || t.rfind("UINT", 0) == 0;
}

}  // namespace

CLI::Option* IntIn(CLI::Option* option, long long lo, long long hi) {
  option->check(CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        const std::optional<long long> v = base::ParseInteger(text);
        if (!v) return "'" + text + "' is not a whole decimal number";
        if (*v < lo || *v > hi) {
          return "'" + text + "' is out of range [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "]";
        }
        return "";
      },
      ""));
  option->type_name("INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return option;
}

void StrictIntegerOptions(CLI::App* app) {
  for (CLI::Option* o : app->get_options()) {
    if (IsIntegerType(o)) o->transform(DecimalInteger());
  }
  for (CLI::App* sub : app->get_subcommands({})) StrictIntegerOptions(sub);
}

CLI::Validator FiniteIn(double lo, double hi) {
  std::ostringstream range;
  range << "[" << lo << ", " << hi << "]";
  return CLI::Validator(
      [lo, hi, r = range.str()](std::string& text) -> std::string {
        const std::optional<double> v = base::ParseFiniteDouble(text);
        if (!v) return "'" + text + "' is not a finite number";
        if (*v < lo || *v > hi) return "'" + text + "' is out of range " + r;
        return "";
      },
      "NUMBER in " + range.str());
}

CLI::Validator NonEmpty() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "empty value; leave the flag out for its default" : "";
      },
      "");
}

void CheckWrithePairs(long long rows_points, long long cols_points) {
  const double pairs = static_cast<double>(std::max(0LL, rows_points - 1)) *
                       static_cast<double>(std::max(0LL, cols_points - 1));
  if (pairs > static_cast<double>(kMaxWrithePairs)) {
    std::ostringstream m;
    m << "writhe matrix of " << rows_points - 1 << " x " << cols_points - 1
      << " segment pairs would need " << pairs * 8.0 / 1e9 << " GB (limit " << kMaxWrithePairs
      << " pairs, " << kMaxWrithePairs * 8 / 1000000 << " MB)";
    throw std::invalid_argument(m.str());
  }
}

namespace {

namespace fs = std::filesystem;

constexpr const char* kManifest = ".topoplan-outputs.json";
constexpr const char* kStagingPrefix = ".topoplan-staging-";
constexpr const char* kJournalPrefix = ".topoplan-journal-";

// The manifest of an output folder: per command, the entries its last run wrote.
nlohmann::json ReadManifest(const fs::path& dir) {
  const fs::path path = dir / kManifest;
  std::error_code ec;
  if (!fs::exists(path, ec)) return nullptr;
  try {
    nlohmann::json j = nlohmann::json::parse(base::ReadFileBounded(path.string(), "manifest"));
    if (j.is_object() && j.value("tool", "") == "topoplan" && j.contains("outputs") &&
        j["outputs"].is_object()) {
      return j;
    }
  } catch (const std::exception&) {
  }
  return nullptr;
}

// Removes staging folders left by processes that no longer run (killed before they could clean
// up).
void RemoveStaleStaging(const fs::path& dir) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(kStagingPrefix, 0) != 0) continue;
    const std::optional<long long> pid =
        base::ParseInteger(name.substr(std::string(kStagingPrefix).size()));
    if (!pid || *pid <= 0) continue;
    if (::kill(static_cast<pid_t>(*pid), 0) != 0 && errno == ESRCH) fs::remove_all(e.path(), ec);
  }
}

// Moves `from` to `to` (replacing it), copying when they are on different file systems.
void MoveEntry(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove_all(to, ec);
  fs::rename(from, to, ec);
  if (!ec) return;
  if (ec.value() == EXDEV) {
    fs::copy(from, to, fs::copy_options::recursive, ec);
    if (!ec) {
      fs::remove_all(from, ec);
      return;
    }
  }
  throw base::WriteError(to.string() +
                         ": cannot move the output into place: " + base::ErrnoText(ec.value()));
}

}  // namespace

OutputDir::OutputDir(const std::string& dir, const std::string& flag, const std::string& command,
                     const std::vector<std::string>& inputs)
    : dir_(dir), command_(command) {
  base::CheckOutputDir(dir, flag, inputs);
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    RemoveStaleStaging(dir);
    // Only a folder of this tool's outputs (or an empty one) is written into: a run never mixes
    // its files with someone else's, and a re-run can replace exactly what it wrote before.
    if (ReadManifest(dir).is_null()) {
      for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(kStagingPrefix, 0) == 0 || name.rfind(kJournalPrefix, 0) == 0) continue;
        throw std::invalid_argument(flag + ": '" + dir + "' holds files topoplan did not write ('" +
                                    name + "', ...); give a new or an empty folder");
      }
    }
  } else {
    fs::create_directories(dir, ec);
    if (ec) throw std::invalid_argument(flag + ": cannot create '" + dir + "': " + ec.message());
    created_ = true;
  }
  // Staged inside the destination: the same file system, so that Commit is a rename.
  staging_ = (fs::path(dir) / (kStagingPrefix + std::to_string(::getpid()))).string();
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) {
    throw std::invalid_argument(flag + ": cannot write into '" + dir + "': " + ec.message());
  }
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  if (created_ && fs::is_empty(dir_, ignored)) fs::remove(dir_, ignored);
}

std::string OutputDir::JournalPath(const std::string& name) const {
  return (fs::path(dir_) / base::StrCat(kJournalPrefix, name)).string();
}

void OutputDir::Commit(bool replace_previous) {
  std::error_code ec;
  nlohmann::json manifest = ReadManifest(dir_);
  if (manifest.is_null()) manifest = {{"tool", "topoplan"}, {"outputs", nlohmann::json::object()}};
  std::vector<std::string> written;
  for (const fs::directory_entry& e : fs::directory_iterator(staging_)) {
    written.push_back(e.path().filename().string());
  }
  std::sort(written.begin(), written.end());
  // What the previous run of this command wrote and this one did not: gone (no stale frames).
  nlohmann::json& outputs = manifest["outputs"];
  std::vector<std::string> owned = written;  // what this command owns in `dir` afterwards
  if (!replace_previous && outputs.contains(command_) && outputs[command_].is_array()) {
    for (const nlohmann::json& old : outputs[command_]) {
      if (old.is_string()) owned.push_back(old.get<std::string>());
    }
    std::sort(owned.begin(), owned.end());
    owned.erase(std::unique(owned.begin(), owned.end()), owned.end());
  }
  if (replace_previous && outputs.contains(command_) && outputs[command_].is_array()) {
    for (const nlohmann::json& old : outputs[command_]) {
      if (!old.is_string()) continue;
      const std::string name = old.get<std::string>();
      if (std::find(written.begin(), written.end(), name) != written.end()) continue;
      if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") {
        continue;
      }
      fs::remove_all(fs::path(dir_) / name, ec);
    }
  }
  for (const std::string& name : written) {
    MoveEntry(fs::path(staging_) / name, fs::path(dir_) / name);
  }
  // Other commands no longer own what this one replaced.
  for (auto& [cmd, list] : outputs.items()) {
    if (cmd == command_ || !list.is_array()) continue;
    nlohmann::json kept = nlohmann::json::array();
    for (const nlohmann::json& n : list) {
      if (n.is_string() &&
          std::find(written.begin(), written.end(), n.get<std::string>()) == written.end()) {
        kept.push_back(n);
      }
    }
    list = kept;
  }
  outputs[command_] = owned;
  base::WriteFileAtomic((fs::path(dir_) / kManifest).string(), manifest.dump(1) + "\n");
  fs::remove_all(staging_, ec);
  committed_ = true;
}

namespace {

volatile std::sig_atomic_t g_signal = 0;
struct sigaction g_old_int, g_old_term;
int g_depth = 0;  // nested StopChecks (the demo runs commands that have their own)
std::optional<std::chrono::steady_clock::time_point> g_deadline;

extern "C" void OnStopSignal(int sig) { g_signal = sig; }

}  // namespace

StopCheck::StopCheck(double timeout_s) : previous_deadline_(g_deadline) {
  if (timeout_s > 0) {
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(timeout_s));
    if (!g_deadline || deadline < *g_deadline) g_deadline = deadline;
  }
  if (g_depth++ > 0) return;  // the outer StopCheck handles the signals
  g_signal = 0;
  struct sigaction sa = {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a second signal terminates as usual
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
}

StopCheck::~StopCheck() {
  g_deadline = previous_deadline_;
  if (--g_depth > 0) return;
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
}

bool StopCheck::Stopped() const {
  return g_signal != 0 || (g_deadline && std::chrono::steady_clock::now() >= *g_deadline);
}

void StopCheck::Poll() const {
  if (g_signal != 0) throw StopRequested(false);
  if (g_deadline && std::chrono::steady_clock::now() >= *g_deadline) throw StopRequested(true);
}

void AddTimeoutFlag(CLI::App* command, double* seconds) {
  command
      ->add_option("--timeout", *seconds,
                   "stop after SECONDS (exit 1, status \"timeout\"); 0 (the default): no time "
                   "limit")
      ->check(FiniteIn(0.0, 1e6));
}

}  // namespace app

namespace app {

std::function<void(long long, long long)> PairProgress(const std::string& label,
                                                       const StopCheck& stop) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  auto last = std::make_shared<Clock::time_point>(start);
  return [label, &stop, start, last](long long done, long long total) {
    stop.Poll();
    const Clock::time_point now = Clock::now();
    if (now - start < std::chrono::seconds(1) || now - *last < std::chrono::seconds(1)) return;
    *last = now;
    Progress("%s: %.0f%% of %.2g segment pairs, %.0f s", label.c_str(),
             100.0 * static_cast<double>(done) / static_cast<double>(std::max(1LL, total)),
             static_cast<double>(total), std::chrono::duration<double>(now - start).count());
  };
}

void AddStreamThreadsFlag(CLI::App* command, int* threads) {
  IntIn(command->add_option("--threads", *threads,
                            "threads (default 0: all cores; the result does not depend on it)"),
        0, 256);
}

}  // namespace app
