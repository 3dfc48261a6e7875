// Frame sequences, contact sheets and optional ffmpeg videos (see frames.h).
#include "render/frames.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include "render/internal/canvas.h"
#include "render/internal/text.h"

namespace render {
namespace fs = std::filesystem;

std::string FindExecutable(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return "";
  std::string all(path);
  size_t start = 0;
  while (start <= all.size()) {
    const size_t end = std::min(all.find(':', start), all.size());
    const fs::path candidate = fs::path(all.substr(start, end - start)) / name;
    if (end > start && access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) {
      return candidate.string();
    }
    start = end + 1;
  }
  return "";
}

namespace {

std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (true) {
    const size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return lines;
    start = end + 1;
  }
}

}  // namespace

Image MakeContactSheet(const std::vector<Image>& thumbnails,
                       const std::vector<std::string>& labels) {
  if (thumbnails.empty() || thumbnails.size() != labels.size()) {
    throw std::invalid_argument("contact sheet: need one label per thumbnail and at least one");
  }
  const int n = static_cast<int>(thumbnails.size());
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const int rows = (n + cols - 1) / cols;
  int cell_w = 0, cell_h = 0;
  size_t label_lines = 1;
  for (const Image& t : thumbnails) {
    cell_w = std::max(cell_w, t.width);
    cell_h = std::max(cell_h, t.height);
  }
  for (const std::string& l : labels) label_lines = std::max(label_lines, SplitLines(l).size());
  constexpr int kGutter = 8, kLine = 16;
  const int label_h = kLine * static_cast<int>(label_lines);
  Image sheet(kGutter + cols * (cell_w + kGutter), kGutter + rows * (cell_h + label_h + kGutter),
              255, 255, 255);
  const internal::Font& font = internal::Font::Regular();
  for (int i = 0; i < n; ++i) {
    const int x = kGutter + (i % cols) * (cell_w + kGutter);
    const int y = kGutter + (i / cols) * (cell_h + label_h + kGutter);
    internal::Blit(&sheet, thumbnails[static_cast<size_t>(i)], x, y);
    internal::StrokeRect(&sheet, x - 1, y - 1, x + thumbnails[static_cast<size_t>(i)].width + 1,
                         y + thumbnails[static_cast<size_t>(i)].height + 1, {160, 160, 160});
    const std::vector<std::string> lines = SplitLines(labels[static_cast<size_t>(i)]);
    for (size_t k = 0; k < lines.size(); ++k) {
      font.Draw(&sheet, x + 0.5f * cell_w,
                y + cell_h + 3 + font.Ascent(11.0f) + kLine * static_cast<float>(k), lines[k],
                11.0f, {40, 40, 40}, internal::Align::kCenter);
    }
  }
  return sheet;
}

std::vector<int> ContactSheetPicks(int n, int m, const std::vector<bool>& keys) {
  if (n < 0 || static_cast<int>(keys.size()) != n) {
    throw std::invalid_argument("contact sheet: one key flag per frame expected");
  }
  std::vector<bool> picked = keys;
  const int num_keys = static_cast<int>(std::count(keys.begin(), keys.end(), true));
  const int even = std::min(n, std::max(0, std::max(1, m) - num_keys));
  for (int k = 0; k < even; ++k) {
    const int i =
        even == 1 ? 0
                  : static_cast<int>(std::lround(static_cast<double>(k) * (n - 1) / (even - 1)));
    picked[static_cast<size_t>(i)] = true;
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i) {
    if (picked[static_cast<size_t>(i)]) out.push_back(i);
  }
  return out;
}

void DrawStamp(Image* image, const std::vector<std::string>& lines) {
  if (lines.empty()) return;
  const internal::Font& font = internal::Font::Regular();
  constexpr float kPx = 13.0f;
  constexpr int kPad = 5, kLine = 17;
  float width = 0.0f;
  for (const std::string& l : lines) width = std::max(width, font.Width(l, kPx));
  const int x1 = std::min(image->width, 2 * kPad + static_cast<int>(std::ceil(width)) + 4);
  const int y1 = std::min(image->height, kPad + kLine * static_cast<int>(lines.size()) + 4);
  for (int y = 2; y < y1; ++y) {
    for (int x = 2; x < x1; ++x) internal::BlendPixel(image, x, y, {255, 255, 255}, 0.75f);
  }
  for (size_t k = 0; k < lines.size(); ++k) {
    font.Draw(image, static_cast<float>(kPad + 2),
              static_cast<float>(kPad + 2) + font.Ascent(kPx) + kLine * static_cast<float>(k),
              lines[k], kPx, {30, 30, 30});
  }
}

namespace internal {

// PNGs written by one background thread in the order pushed, at most kMaxPending waiting. The
// first failure is kept and rethrown by the next Push or by Drain; later frames are dropped.
class PngQueue {
 public:
  PngQueue() : thread_([this] { Run(); }) {}
  ~PngQueue() {
    try {
      Drain();
    } catch (...) {  // the owner's Finish reports errors; a destructor must not throw
    }
  }
  PngQueue(const PngQueue&) = delete;
  PngQueue& operator=(const PngQueue&) = delete;

  void Push(std::string path, Image image) {
    std::unique_lock<std::mutex> lock(mutex_);
    space_.wait(lock, [&] { return jobs_.size() < kMaxPending || error_; });
    if (error_) std::rethrow_exception(error_);
    jobs_.emplace_back(std::move(path), std::move(image));
    ready_.notify_one();
  }

  // Waits until every pushed PNG is written and stops the thread; rethrows the first failure.
  void Drain() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
      ready_.notify_one();
    }
    if (thread_.joinable()) thread_.join();
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  static constexpr size_t kMaxPending = 4;

  void Run() {
    while (true) {
      std::pair<std::string, Image> job;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        ready_.wait(lock, [&] { return !jobs_.empty() || closed_; });
        if (jobs_.empty()) return;
        job = std::move(jobs_.front());
        jobs_.pop_front();
        space_.notify_one();
        if (error_) continue;
      }
      try {
        WritePng(job.first, job.second);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
        space_.notify_all();
      }
    }
  }

  std::mutex mutex_;
  std::condition_variable ready_, space_;
  std::deque<std::pair<std::string, Image>> jobs_;
  bool closed_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: started once the members it uses exist
};

}  // namespace internal

namespace {

// Runs one ffmpeg for all `jobs` (input i mapped to output i). False without ffmpeg or when it
// fails.
bool EncodeVideos(const std::vector<VideoBatch::Job>& jobs) {
  if (jobs.empty()) return true;
  const std::string ffmpeg = FindExecutable("ffmpeg");
  if (ffmpeg.empty()) return false;
  std::vector<std::string> args = {ffmpeg, "-y", "-loglevel", "error"};
  for (const VideoBatch::Job& job : jobs) {
    args.insert(args.end(), {"-framerate", std::to_string(job.fps), "-i", job.pattern});
  }
  for (size_t i = 0; i < jobs.size(); ++i) {
    args.insert(args.end(), {"-map", std::to_string(i)});
    if (jobs[i].gif) {
      args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse"});
    } else {
      // yuv420p needs even sizes; H.264 for players everywhere. x264's veryfast preset: about
      // the same file size as its default (medium) for these frames at a quarter less CPU. One
      // encoder thread: the callers already run one process per core, and x264's thread pool
      // cost a third of its CPU on these short, small videos (same file size).
      args.insert(args.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-preset",
                               "veryfast", "-threads", "1", "-pix_fmt", "yuv420p"});
    }
    args.push_back(jobs[i].out);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  return pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) &&
         WEXITSTATUS(status) == 0;
}

}  // namespace

VideoBatch::~VideoBatch() { Flush(); }

void VideoBatch::Add(const std::string& pattern, const std::string& out, int fps, bool gif) {
  jobs_.push_back({pattern, out, fps, gif});
  if (static_cast<int>(jobs_.size()) >= max_pending_) Flush();
}

bool VideoBatch::Flush() {
  const std::vector<Job> jobs = std::move(jobs_);
  jobs_.clear();
  return EncodeVideos(jobs);
}

FrameWriter::FrameWriter(const std::string& dir, const FrameWriterOptions& options)
    : dir_(dir), options_(options) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_)) throw std::runtime_error(dir_ + ": cannot create folder");
}

std::string FrameWriter::Add(const Image& frame, const std::string& label, bool key) {
  char name[64];
  std::snprintf(name, sizeof(name), "%05d.png", size());
  const std::string path = (fs::path(dir_) / (options_.prefix + name)).string();
  if (!pngs_) pngs_ = std::make_unique<internal::PngQueue>();
  pngs_->Push(path, frame);
  sequence_.frames.push_back(path);
  if (options_.contact_sheet) {
    const int w = std::min(options_.thumbnail_width, frame.width);
    const int h = std::max(
        1, static_cast<int>(std::lround(static_cast<double>(w) * frame.height / frame.width)));
    thumbnails_.push_back(Downscale(frame, w, h));
  }
  labels_.push_back(label.empty() ? "frame " + std::to_string(size() - 1) : label);
  keys_.push_back(key);
  return path;
}

void FrameWriter::SetLabel(int index, const std::string& label, bool key) {
  if (index < 0 || index >= size()) {
    throw std::out_of_range("frame " + std::to_string(index) + " does not exist");
  }
  labels_[static_cast<size_t>(index)] = label;
  if (key) keys_[static_cast<size_t>(index)] = true;
}

FrameWriter::~FrameWriter() = default;

FrameSequence FrameWriter::Finish() {
  if (pngs_) {
    pngs_->Drain();  // the contact sheet and ffmpeg come after every frame is on disk
    pngs_.reset();
  }
  const int n = size();
  if (options_.contact_sheet && n > 0) {
    // Key frames, then evenly sampled ones (always including the first and the last).
    std::vector<Image> picked;
    std::vector<std::string> labels;
    for (int i : ContactSheetPicks(n, options_.contact_sheet_max_frames, keys_)) {
      picked.push_back(thumbnails_[static_cast<size_t>(i)]);
      labels.push_back(labels_[static_cast<size_t>(i)]);
    }
    sequence_.contact_sheet = (fs::path(dir_) / "contact_sheet.png").string();
    WritePng(sequence_.contact_sheet, MakeContactSheet(picked, labels));
  }
  thumbnails_.clear();
  if (options_.video && n > 0) {
    const std::string out =
        (fs::path(dir_) / (options_.prefix + (options_.gif ? "video.gif" : "video.mp4"))).string();
    const std::string pattern = (fs::path(dir_) / (options_.prefix + "%05d.png")).string();
    if (options_.video_batch != nullptr) {
      if (!FindExecutable("ffmpeg").empty()) {
        options_.video_batch->Add(pattern, out, options_.fps, options_.gif);
        sequence_.video = out;
      }
    } else if (EncodeVideos({{pattern, out, options_.fps, options_.gif}})) {
      sequence_.video = out;
    }
  }
  return sequence_;
}

}  // namespace render
