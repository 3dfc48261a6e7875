#include "app/cli/io.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "base/file_read.h"

namespace app {

namespace {
bool StderrIsTerminal() {
  static const bool tty = isatty(STDERR_FILENO) == 1;
  return tty;
}
}  // namespace

void Progress(const char* format, ...) {
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
  if (StderrIsTerminal()) std::fputc('\n', stderr);
}

void WriteFileAtomic(const std::string& path, const std::string& contents) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const fs::path tmp = target.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error(path + ": cannot write output file");
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw std::runtime_error(path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(path + ": cannot move output into place");
  }
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

void CheckOutputDir(const std::string& dir, const std::string& flag) {
  namespace fs = std::filesystem;
  if (dir.empty()) throw std::invalid_argument(flag + ": empty output path");
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(dir), ec);
  if (ec) throw std::invalid_argument(flag + ": '" + dir + "': " + ec.message());
  // The folder itself, or its nearest existing ancestor (which would hold the new folders).
  while (!fs::exists(p, ec)) {
    if (!p.has_parent_path() || p.parent_path() == p) break;
    p = p.parent_path();
  }
  if (!fs::is_directory(p, ec)) {
    throw std::invalid_argument(flag + ": '" + dir + "': " + p.string() + " is not a folder");
  }
  if (::access(p.c_str(), W_OK | X_OK) != 0) {
    throw std::invalid_argument(flag + ": '" + dir + "': folder " + p.string() +
                                " is not writable");
  }
}

void CheckOutputFile(const std::string& path, const std::string& flag) {
  namespace fs = std::filesystem;
  if (path.empty()) throw std::invalid_argument(flag + ": empty output path");
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw std::invalid_argument(flag + ": '" + path + "' is a folder, expected a file name");
  }
  const fs::path parent = fs::path(path).parent_path();
  CheckOutputDir(parent.empty() ? "." : parent.string(), flag);
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

OutputDir::OutputDir(const std::string& dir, const std::string& flag) : dir_(dir) {
  namespace fs = std::filesystem;
  CheckOutputDir(dir, flag);
  fs::path target = fs::path(dir).lexically_normal();
  if (!target.has_filename()) target = target.parent_path();  // "out/" -> "out"
  staging_ = target.string() + ".partial-" + std::to_string(::getpid());
  std::error_code ec;
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) throw std::invalid_argument(flag + ": cannot create " + staging_ + ": " + ec.message());
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ignored;
  std::filesystem::remove_all(staging_, ignored);
}

void OutputDir::Commit() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(dir_, ec)) {
    if (fs::path(dir_).has_parent_path()) fs::create_directories(fs::path(dir_).parent_path(), ec);
    fs::rename(staging_, dir_, ec);  // one atomic step
    if (!ec) {
      committed_ = true;
      return;
    }
    fs::create_directories(dir_, ec);
  }
  for (const fs::directory_entry& e : fs::directory_iterator(staging_)) {
    const fs::path to = fs::path(dir_) / e.path().filename();
    if (e.is_directory()) fs::remove_all(to, ec);
    fs::rename(e.path(), to, ec);
    if (ec) throw std::runtime_error(to.string() + ": cannot move output into place");
  }
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
  command->add_option("--timeout", *seconds, "stop after SECONDS (exit 1, status \"timeout\")")
      ->check(FiniteIn(0.0, 1e6));
}

void AddFormatsFlag(CLI::App* command, std::vector<render::FigureFormat>* formats) {
  *formats = {render::FigureFormat::kPng};
  command
      ->add_option_function<std::string>(
          "--formats",
          [formats](const std::string& list) {
            *formats = render::ParseFigureFormats(list, "--formats");
          },
          "figure formats, a comma-separated subset of png,svg,pdf (default png)")
      ->check([](const std::string& list) {
        try {
          render::ParseFigureFormats(list, "--formats");
        } catch (const std::invalid_argument& e) {
          return std::string(e.what()).substr(std::string("--formats: ").size());
        }
        return std::string();
      });
}

}  // namespace app
