// PNG round trips, bad-input errors, downscaling and hashing (render/image.h).
#include "render/image.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace render {
namespace {

std::string TempPath(const std::string& name) {
  const auto dir = std::filesystem::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "image_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

Image Gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = static_cast<std::uint8_t>(x * 255 / (w - 1));
      p[1] = static_cast<std::uint8_t>(y * 255 / (h - 1));
      p[2] = static_cast<std::uint8_t>((x * y) % 256);
      p[3] = static_cast<std::uint8_t>(255 - (x % 7));
    }
  }
  return img;
}

TEST(ImageTest, PngRoundTripIsLossless) {
  const Image img = Gradient(37, 21);
  for (int level : {0, 2, 9}) {
    const Image back = DecodePng(EncodePng(img, level), "memory");
    EXPECT_TRUE(SameImage(img, back)) << "zlib level " << level;
  }
  const std::string path = TempPath("gradient.png");
  WritePng(path, img);
  EXPECT_TRUE(SameImage(img, ReadPng(path)));
}

TEST(ImageTest, EncodingIsDeterministic) {
  const Image img = Gradient(64, 48);
  EXPECT_EQ(EncodePng(img), EncodePng(img));
}

TEST(ImageTest, BadInputNamesTheFile) {
  try {
    ReadPng("/nonexistent/x.png");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.png"), std::string::npos);
  }
  const std::string text = TempPath("not_a_png.png");
  std::ofstream(text) << "hello, this is text\n";
  try {
    ReadPng(text);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not a PNG"), std::string::npos) << e.what();
  }
  // A PNG signature followed by garbage.
  std::string truncated = EncodePng(Gradient(8, 8)).substr(0, 40);
  EXPECT_THROW(DecodePng(truncated, "truncated"), std::invalid_argument);
}

// Halving (the frames' thumbnails take a fast path) averages each 2 × 2 block, rounding halves up,
// as every other size does.
TEST(ImageTest, DownscaleByHalfAveragesTwoByTwoBlocks) {
  Image img(10, 6);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 10; ++x) {
      for (int c = 0; c < 4; ++c)
        img.at(x, y)[c] = static_cast<std::uint8_t>((37 * x + 91 * y + 53 * c) % 256);
    }
  }
  const Image half = Downscale(img, 5, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      for (int c = 0; c < 4; ++c) {
        const unsigned sum = img.at(2 * x, 2 * y)[c] + img.at(2 * x + 1, 2 * y)[c] +
                             img.at(2 * x, 2 * y + 1)[c] + img.at(2 * x + 1, 2 * y + 1)[c];
        ASSERT_EQ(half.at(x, y)[c], (sum + 2) / 4) << x << "," << y << "," << c;
      }
    }
  }
}

TEST(ImageTest, DownscaleAveragesBlocks) {
  Image img(4, 2, 0, 0, 0);
  img.at(0, 0)[0] = 200;
  img.at(1, 0)[0] = 100;
  img.at(0, 1)[0] = 0;
  img.at(1, 1)[0] = 100;
  const Image small = Downscale(img, 2, 1);
  EXPECT_EQ(small.at(0, 0)[0], 100);  // (200+100+0+100)/4
  EXPECT_EQ(small.at(1, 0)[0], 0);
}

TEST(ImageTest, HashSeesOnePixel) {
  Image a = Gradient(16, 16);
  Image b = a;
  EXPECT_EQ(HashImage(a), HashImage(b));
  b.at(3, 4)[1] ^= 1;
  EXPECT_NE(HashImage(a), HashImage(b));
}

}  // namespace
}  // namespace render
