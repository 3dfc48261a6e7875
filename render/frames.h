// Frame sequences: numbered PNGs in a folder, a contact sheet, and an MP4 (or GIF) when an
// `ffmpeg` executable is on PATH (optional: skipped quietly otherwise).
//
// Layout of a finished sequence in `dir`:
//   <prefix>00000.png, <prefix>00001.png, ...   every frame (libpng, fast settings)
//   contact_sheet.png                           thumbnails in a grid, each with its label
//   <prefix>video.mp4 (or .gif)                 when ffmpeg exists and video is enabled
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/image.h"

namespace render {

class VideoBatch;

struct FrameWriterOptions {
  std::string prefix = "frame_";
  bool contact_sheet = true;
  int contact_sheet_max_frames = 36;  // evenly sampled when there are more frames
  int thumbnail_width = 240;          // pixels; height keeps the aspect ratio
  bool video = true;                  // MP4 (H.264) or GIF via ffmpeg, if installed
  bool gif = false;                   // GIF instead of MP4
  int fps = 10;
  // Not null: Finish() queues the video in this batch instead of running ffmpeg itself (the batch
  // must outlive the writer); FrameSequence::video is then where the batch writes it.
  VideoBatch* video_batch = nullptr;
};

struct FrameSequence {
  std::vector<std::string> frames;  // paths of the PNGs in order
  std::string contact_sheet;        // empty when disabled or no frames
  std::string video;                // empty when skipped (no ffmpeg, disabled, or it failed)
};

namespace internal {
class PngQueue;
}  // namespace internal

// Writes frames one at a time and keeps a thumbnail of each for the contact sheet. The PNGs are
// encoded and written by one background thread, in order, at most a few frames behind Add (so
// memory stays bounded and the caller renders the next frame meanwhile); Finish() waits for them.
// The files do not depend on this (the same bytes as written inline). Frames may differ in size;
// the contact sheet uses the first frame's aspect ratio.
class FrameWriter {
 public:
  // Creates `dir` if needed. Throws std::runtime_error when it cannot be created.
  explicit FrameWriter(const std::string& dir, const FrameWriterOptions& options = {});
  ~FrameWriter();  // waits for the pending PNGs (errors are then dropped: call Finish)
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Queues the next frame for writing; returns its path. A failed write of an earlier frame is
  // thrown here or by Finish() (base::WriteError, as render::WritePng). `label` captions its
  // contact-sheet thumbnail (empty: "frame N"; '\n' starts another line). `key` frames are always
  // on the contact sheet, the others fill the remaining places evenly (the first and the last
  // always included).
  std::string Add(const Image& frame, const std::string& label = "", bool key = false);

  // Replaces the label of frame `index` (0 <= index < size()); `key` also makes it a key frame,
  // e.g. to say why a sequence ended early. Throws std::out_of_range for a bad index.
  void SetLabel(int index, const std::string& label, bool key = false);

  // Waits until every frame is written, then writes the contact sheet and the video; call once
  // at the end.
  FrameSequence Finish();

  int size() const { return static_cast<int>(sequence_.frames.size()); }

 private:
  std::string dir_;
  FrameWriterOptions options_;
  FrameSequence sequence_;
  std::vector<Image> thumbnails_;
  std::vector<std::string> labels_;
  std::vector<bool> keys_;
  std::unique_ptr<internal::PngQueue> pngs_;  // started by the first Add
};

// Videos of finished frame sequences encoded together by one ffmpeg process per flush, which
// pays ffmpeg's start-up once instead of once per video; each output is the same file as a
// FrameWriter encoding it alone writes. Without ffmpeg on PATH, nothing is written.
class VideoBatch {
 public:
  explicit VideoBatch(int max_pending = 8) : max_pending_(max_pending) {}
  ~VideoBatch();  // flushes (a failure then goes unreported)
  VideoBatch(const VideoBatch&) = delete;
  VideoBatch& operator=(const VideoBatch&) = delete;

  // Queues `out` from the numbered PNGs `pattern` (printf style, e.g. DIR/frame_%05d.png, all on
  // disk); flushes once max_pending videos are queued.
  void Add(const std::string& pattern, const std::string& out, int fps, bool gif);
  // Encodes every queued video; false when ffmpeg is missing or failed (none of them written).
  bool Flush();

  struct Job {
    std::string pattern, out;
    int fps = 10;
    bool gif = false;
  };

 private:
  int max_pending_;
  std::vector<Job> jobs_;
};

// Contact sheet of `thumbnails` in a grid of ceil(sqrt(n)) columns, each labelled with
// labels[i] below it (white background, 8 px gutters, 16 px per label line; '\n' separates lines).
// Throws std::invalid_argument when empty or when labels and thumbnails differ in count.
Image MakeContactSheet(const std::vector<Image>& thumbnails,
                       const std::vector<std::string>& labels);

// Indices of at most max(m, number of keys) of n frames for a contact sheet, ascending: every key
// frame (keys[i], keys.size() == n), then the first, the last and evenly spaced others up to m.
std::vector<int> ContactSheetPicks(int n, int m, const std::vector<bool>& keys);

// Writes `lines` into the top-left corner of `image` (13 px DejaVu Sans, dark grey on a
// translucent white box), e.g. a time stamp and scenario name on a rendered frame.
void DrawStamp(Image* image, const std::vector<std::string>& lines);

// Full path of an executable `name` found on PATH, or empty.
std::string FindExecutable(const std::string& name);

}  // namespace render
