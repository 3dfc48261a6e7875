// Frame sequences and contact sheets (render/frames.h).
#include "render/frames.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>

namespace render {
namespace {

namespace fs = std::filesystem;

TEST(FramesTest, WritesNumberedFramesAndAContactSheet) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "frames_test";
  fs::remove_all(dir);
  FrameWriterOptions o;
  o.thumbnail_width = 40;
  o.video = false;
  FrameWriter writer(dir.string(), o);
  for (int i = 0; i < 5; ++i) {
    writer.Add(Image(80, 60, static_cast<std::uint8_t>(50 * i), 100, 200));
  }
  const FrameSequence seq = writer.Finish();
  ASSERT_EQ(seq.frames.size(), 5u);
  EXPECT_EQ(fs::path(seq.frames[3]).filename(), "frame_00003.png");
  for (const std::string& f : seq.frames) EXPECT_TRUE(fs::exists(f)) << f;
  EXPECT_EQ(ReadPng(seq.frames[4]).at(0, 0)[0], 200);
  ASSERT_FALSE(seq.contact_sheet.empty());
  const Image sheet = ReadPng(seq.contact_sheet);
  // 5 thumbnails of 40x30 in a 3x2 grid with 8 px gutters and 16 px labels.
  EXPECT_EQ(sheet.width, 8 + 3 * (40 + 8));
  EXPECT_EQ(sheet.height, 8 + 2 * (30 + 16 + 8));
  EXPECT_TRUE(seq.video.empty());
}

TEST(FramesTest, VideoIsSkippedQuietlyWithoutFfmpeg) {
  // Hide any ffmpeg by emptying PATH for the duration of Finish().
  const std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", "/nonexistent-topoplan", 1);
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "frames_video_test";
  fs::remove_all(dir);
  FrameWriter writer(dir.string());
  writer.Add(Image(32, 32, 0, 0, 0));
  const FrameSequence seq = writer.Finish();
  setenv("PATH", saved.c_str(), 1);
  EXPECT_TRUE(seq.video.empty());
  EXPECT_FALSE(seq.contact_sheet.empty());
}

TEST(FramesTest, WritesAnMp4WhenFfmpegExists) {
  if (FindExecutable("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg is not installed (optional)";
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "frames_mp4_test";
  fs::remove_all(dir);
  FrameWriterOptions o;
  o.contact_sheet = false;
  FrameWriter writer(dir.string(), o);
  for (int i = 0; i < 3; ++i) writer.Add(Image(63, 47, static_cast<std::uint8_t>(80 * i), 50, 90));
  const FrameSequence seq = writer.Finish();
  ASSERT_FALSE(seq.video.empty());
  EXPECT_EQ(fs::path(seq.video).filename(), "frame_video.mp4");
  EXPECT_GT(fs::file_size(seq.video), 100u);
}

TEST(FramesTest, FindExecutable) {
  EXPECT_FALSE(FindExecutable("sh").empty());
  EXPECT_TRUE(FindExecutable("no-such-program-topoplan").empty());
}

}  // namespace
}  // namespace render
