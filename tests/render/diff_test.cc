// The perceptual diff and the golden-image check (render/diff.h).
#include "render/diff.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>

namespace render {
namespace {

namespace fs = std::filesystem;

// A black disc of radius r centred at (cx, cy) on white, anti-aliased by exact-ish coverage
// (16x16 supersampling per pixel).
Image Disc(int w, int h, double cx, double cy, double r) {
  Image img(w, h, 255, 255, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int inside = 0;
      for (int sy = 0; sy < 16; ++sy) {
        for (int sx = 0; sx < 16; ++sx) {
          const double px = x + (sx + 0.5) / 16.0, py = y + (sy + 0.5) / 16.0;
          inside += std::hypot(px - cx, py - cy) <= r;
        }
      }
      const auto v = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - inside / 256.0)));
      std::uint8_t* p = img.at(x, y);
      p[0] = p[1] = p[2] = v;
    }
  }
  return img;
}

TEST(DiffTest, DefaultTolerance) {
  EXPECT_EQ(DefaultAllowedDiffPixels(320, 240), 10);
  EXPECT_EQ(DefaultAllowedDiffPixels(640, 480), 16);  // ceil(15.36)
  EXPECT_EQ(DefaultAllowedDiffPixels(1280, 720), 47);
}

TEST(DiffTest, IdenticalImagesPass) {
  const Image a = Disc(80, 60, 40, 30, 15);
  const DiffResult r = CompareImages(a, a);
  EXPECT_TRUE(r.identical);
  EXPECT_TRUE(r.passed);
  EXPECT_EQ(r.diff_pixels, 0);
  EXPECT_EQ(r.changed_pixels, 0);
}

TEST(DiffTest, SubpixelShiftOfAnEdgeIsAntiAliasingOnly) {
  // Moving an anti-aliased disc by a fraction of a pixel changes only edge pixels.
  const Image a = Disc(80, 60, 40.0, 30.0, 15.0);
  const Image b = Disc(80, 60, 40.3, 30.2, 15.0);
  const DiffResult r = CompareImages(a, b);
  EXPECT_GT(r.changed_pixels, 20);
  EXPECT_GT(r.aa_pixels, 0);
  EXPECT_LE(r.diff_pixels, r.allowed);
  EXPECT_TRUE(r.passed);
  // Counting anti-aliased pixels too turns the same change into a failure.
  DiffOptions strict;
  strict.include_aa = true;
  strict.max_diff_pixels = 0;
  EXPECT_FALSE(CompareImages(a, b, strict).passed);
}

TEST(DiffTest, SmallRealChangeIsCaught) {
  const Image a = Disc(80, 60, 40, 30, 15);
  Image b = a;
  // A 4x4 dark "bead" appears in the white background.
  for (int y = 5; y < 9; ++y) {
    for (int x = 5; x < 9; ++x) b.at(x, y)[0] = b.at(x, y)[1] = b.at(x, y)[2] = 20;
  }
  const DiffResult r = CompareImages(a, b);
  EXPECT_EQ(r.diff_pixels, 16);
  DiffOptions loose;
  loose.max_diff_pixels = 16;
  EXPECT_TRUE(CompareImages(a, b, loose).passed);
  loose.max_diff_pixels = 15;
  EXPECT_FALSE(CompareImages(a, b, loose).passed);
  // Counted pixels are red in the visualisation.
  EXPECT_EQ(r.visual.at(6, 6)[0], 230);
  EXPECT_EQ(r.visual.at(6, 6)[1], 0);
}

TEST(DiffTest, TinyColourShiftIsBelowThreshold) {
  const Image a(40, 30, 100, 150, 200);
  const Image b(40, 30, 102, 150, 200);
  const DiffResult r = CompareImages(a, b);
  EXPECT_EQ(r.changed_pixels, 40 * 30);
  EXPECT_EQ(r.diff_pixels, 0);
  EXPECT_EQ(r.max_channel_delta, 2);
}

TEST(DiffTest, SizeMismatchThrows) {
  EXPECT_THROW(CompareImages(Image(10, 10), Image(10, 11)), std::invalid_argument);
}

TEST(DiffTest, CheckSnapshotMissingUpdateAndFailure) {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "diff_test";
  fs::remove_all(dir);
  const std::string golden = (dir / "golden" / "disc.png").string();
  const std::string artefacts = (dir / "artefacts").string();
  const Image a = Disc(40, 30, 20, 15, 8);
  unsetenv("UPDATE_SNAPSHOTS");
  SnapshotResult r = CheckSnapshot(a, golden, artefacts);
  EXPECT_FALSE(r.passed);
  EXPECT_TRUE(fs::exists(dir / "artefacts" / "disc.png")) << r.message;
  EXPECT_FALSE(fs::exists(golden));

  setenv("UPDATE_SNAPSHOTS", "1", 1);
  r = CheckSnapshot(a, golden, artefacts);
  unsetenv("UPDATE_SNAPSHOTS");
  EXPECT_TRUE(r.passed);
  EXPECT_TRUE(r.updated);
  EXPECT_TRUE(SameImage(ReadPng(golden), a));

  EXPECT_TRUE(CheckSnapshot(a, golden, artefacts).passed);
  Image b = a;
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 6; ++x) b.at(x, y)[1] = 0;
  }
  r = CheckSnapshot(b, golden, artefacts);
  EXPECT_FALSE(r.passed);
  for (const char* f : {"disc.png", "disc-expected.png", "disc-diff.png", "disc-absdiff.png"}) {
    EXPECT_TRUE(fs::exists(dir / "artefacts" / f)) << f;
  }
  EXPECT_NE(r.message.find("36 different pixels"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace render
