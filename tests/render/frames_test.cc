// Frame sequences and contact sheets (render/frames.h).
#include "render/frames.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

// Videos queued in a VideoBatch (one ffmpeg for several) are the files each FrameWriter writes
// alone, byte for byte, whatever the batch size; they appear on Flush (or when the batch is full).
TEST(FramesTest, BatchedVideosEqualVideosEncodedAlone) {
  if (FindExecutable("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg is not installed (optional)";
  const fs::path root = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "frames_batch_test";
  fs::remove_all(root);
  auto write = [&](const std::string& name, int k, VideoBatch* batch) {
    FrameWriterOptions o;
    o.contact_sheet = false;
    o.gif = k == 2;  // one GIF among the MP4s
    o.video_batch = batch;
    FrameWriter writer((root / name).string(), o);
    for (int i = 0; i < 4; ++i) {
      writer.Add(Image(40 + 6 * k, 30 + 2 * k, static_cast<std::uint8_t>(60 * i), 20 * k, 90));
    }
    return writer.Finish().video;
  };
  auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  VideoBatch batch(2);
  std::vector<std::string> alone, batched;
  for (int k = 0; k < 3; ++k) {
    alone.push_back(write("alone_" + std::to_string(k), k, nullptr));
    batched.push_back(write("batched_" + std::to_string(k), k, &batch));
  }
  EXPECT_TRUE(fs::exists(batched[0]));   // the batch was full after two: flushed
  EXPECT_FALSE(fs::exists(batched[2]));  // queued
  ASSERT_TRUE(batch.Flush());
  for (int k = 0; k < 3; ++k) {
    ASSERT_FALSE(alone[k].empty());
    ASSERT_TRUE(fs::exists(batched[k])) << batched[k];
    EXPECT_EQ(fs::path(batched[k]).extension(), k == 2 ? ".gif" : ".mp4");
    EXPECT_EQ(bytes(alone[k]), bytes(batched[k])) << k;
  }
}

TEST(FramesTest, LabelsKeyFramesAndMultiLineLabels) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "frames_label_test";
  fs::remove_all(dir);
  FrameWriterOptions o;
  o.thumbnail_width = 40;
  o.video = false;
  o.contact_sheet_max_frames = 4;
  FrameWriter writer(dir.string(), o);
  for (int i = 0; i < 10; ++i) writer.Add(Image(80, 60, 0, 0, 0), "t = " + std::to_string(i));
  writer.SetLabel(4, "t = 4\nobject dropped", /*key=*/true);
  EXPECT_THROW(writer.SetLabel(10, "x"), std::out_of_range);
  const FrameSequence seq = writer.Finish();
  const Image sheet = ReadPng(seq.contact_sheet);
  // 4 thumbnails (key frame 4 + 3 evenly spaced) in a 2x2 grid; labels of two 16 px lines.
  EXPECT_EQ(sheet.width, 8 + 2 * (40 + 8));
  EXPECT_EQ(sheet.height, 8 + 2 * (30 + 32 + 8));
}

TEST(FramesTest, ContactSheetPicksKeepKeyFrames) {
  std::vector<bool> keys(10, false);
  EXPECT_EQ(ContactSheetPicks(10, 4, keys), (std::vector<int>{0, 3, 6, 9}));
  keys[4] = true;
  EXPECT_EQ(ContactSheetPicks(10, 4, keys), (std::vector<int>{0, 4, 5, 9}));
  keys.assign(10, true);
  EXPECT_EQ(ContactSheetPicks(10, 4, keys).size(), 10u);  // every key frame, even beyond m
  EXPECT_EQ(ContactSheetPicks(3, 36, std::vector<bool>(3, false)), (std::vector<int>{0, 1, 2}));
  EXPECT_THROW(ContactSheetPicks(3, 4, keys), std::invalid_argument);
}

TEST(FramesTest, StampDarkensTextInTheTopLeftCorner) {
  Image image(200, 100, 0, 0, 255);
  DrawStamp(&image, {"unwrap", "t = 1.25 s"});
  // A light box behind dark text in the corner; the rest of the image is untouched.
  EXPECT_GT(image.at(3, 3)[0], 150);
  int dark = 0;
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 100; ++x) dark += image.at(x, y)[0] < 100 && image.at(x, y)[2] < 150;
  }
  EXPECT_GT(dark, 20);
  EXPECT_EQ(image.at(199, 99)[2], 255);
  EXPECT_EQ(image.at(199, 99)[0], 0);
}

TEST(FramesTest, FindExecutable) {
  EXPECT_FALSE(FindExecutable("sh").empty());
  EXPECT_TRUE(FindExecutable("no-such-program-topoplan").empty());
}

// The PNGs are written by a background thread: after Finish every file holds exactly the bytes
// EncodePng gives inline, in order, also for more frames than the queue holds.
TEST(FramesTest, BackgroundWritesEqualInlineEncoding) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "frames_test_background";
  fs::remove_all(dir);
  FrameWriterOptions o;
  o.video = false;
  FrameWriter writer(dir.string(), o);
  std::vector<Image> images;
  for (int i = 0; i < 12; ++i) {
    Image img(64 + i, 48, static_cast<std::uint8_t>(20 * i), 90,
              static_cast<std::uint8_t>(255 - i));
    img.at(i, 3)[1] = 7;  // each frame different
    images.push_back(img);
    writer.Add(img);
  }
  const FrameSequence seq = writer.Finish();
  ASSERT_EQ(seq.frames.size(), images.size());
  for (size_t i = 0; i < images.size(); ++i) {
    std::ifstream in(seq.frames[i], std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(bytes, EncodePng(images[i])) << seq.frames[i];
  }
}

// A frame that cannot be written (its folder was replaced by a file) is reported by Add or
// Finish, not lost.
TEST(FramesTest, BackgroundWriteFailureIsThrown) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "frames_test_failure";
  fs::remove_all(dir);
  FrameWriterOptions o;
  o.video = false;
  o.contact_sheet = false;
  FrameWriter writer(dir.string(), o);
  fs::remove_all(dir);
  std::ofstream(dir) << "not a folder";
  EXPECT_ANY_THROW({
    for (int i = 0; i < 10; ++i) writer.Add(Image(16, 16, 0, 0, 0));
    writer.Finish();
  });
}

}  // namespace
}  // namespace render
