// Frame sequences: numbered PNGs in a folder, a contact sheet, and an MP4 (or GIF) when an
// `ffmpeg` executable is on PATH (optional: skipped quietly otherwise).
//
// Layout of a finished sequence in `dir`:
//   <prefix>00000.png, <prefix>00001.png, ...   every frame (libpng, fast settings)
//   contact_sheet.png                           thumbnails in a grid, each labelled with its index
//   <prefix>video.mp4 (or .gif)                 when ffmpeg exists and video is enabled
#pragma once

#include <string>
#include <vector>

#include "render/image.h"

namespace render {

struct FrameWriterOptions {
  std::string prefix = "frame_";
  bool contact_sheet = true;
  int contact_sheet_max_frames = 36;  // evenly sampled when there are more frames
  int thumbnail_width = 240;          // pixels; height keeps the aspect ratio
  bool video = true;                  // MP4 (H.264) or GIF via ffmpeg, if installed
  bool gif = false;                   // GIF instead of MP4
  int fps = 10;
};

struct FrameSequence {
  std::vector<std::string> frames;  // paths of the PNGs in order
  std::string contact_sheet;        // empty when disabled or no frames
  std::string video;                // empty when skipped (no ffmpeg, disabled, or it failed)
};

// Writes frames one at a time (each PNG is written immediately, so memory stays bounded) and
// keeps a thumbnail of each for the contact sheet. Frames may differ in size; the contact sheet
// uses the first frame's aspect ratio.
class FrameWriter {
 public:
  // Creates `dir` if needed. Throws std::runtime_error when it cannot be created.
  explicit FrameWriter(const std::string& dir, const FrameWriterOptions& options = {});

  // Writes the next frame; returns its path.
  std::string Add(const Image& frame);

  // Writes the contact sheet and the video; call once at the end.
  FrameSequence Finish();

  int size() const { return static_cast<int>(sequence_.frames.size()); }

 private:
  std::string dir_;
  FrameWriterOptions options_;
  FrameSequence sequence_;
  std::vector<Image> thumbnails_;
};

// Contact sheet of `thumbnails` in a grid of ceil(sqrt(n)) columns, each labelled with
// labels[i] (white background, 8 px gutters). Throws std::invalid_argument when empty or when
// labels and thumbnails differ in count.
Image MakeContactSheet(const std::vector<Image>& thumbnails,
                       const std::vector<std::string>& labels);

// Full path of an executable `name` found on PATH, or empty.
std::string FindExecutable(const std::string& name);

}  // namespace render
