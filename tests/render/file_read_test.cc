// Bounded reading of render/'s input files (through base/file_read.h): PNG images and fonts
// are refused quickly when they are endless (/dev/zero), huge or a named pipe nobody writes to.
#include "base/file_read.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "render/image.h"
#include "render/internal/text.h"
#include "render/offscreen_context.h"

namespace render {
namespace {

namespace fs = std::filesystem;

fs::path TempDir() {
  const fs::path dir = fs::path(TOPOPLAN_BINARY_DIR) / "test-tmp" / "file_read_test";
  fs::create_directories(dir);
  return dir;
}

// A named pipe with no writer (opening it for reading with std::ifstream would block for ever).
std::string Fifo(const std::string& name) {
  const fs::path p = TempDir() / name;
  fs::remove(p);
  if (::mkfifo(p.c_str(), 0600) != 0) throw std::runtime_error("mkfifo failed: " + p.string());
  return p.string();
}

// Runs `f`, expects an exception of type E whose message contains every one of `parts`, within
// 5 seconds.
template <typename E, typename F>
void ExpectRefused(F f, std::initializer_list<std::string> parts) {
  const auto start = std::chrono::steady_clock::now();
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const E& e) {
    for (const std::string& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(ReadPngBounded, DevZeroFifoAndHugeFileAreRefused) {
  ExpectRefused<std::invalid_argument>([] { ReadPng("/dev/zero"); }, {"/dev/zero", "larger than"});
  const std::string fifo = Fifo("image.fifo");
  ExpectRefused<std::invalid_argument>([&] { ReadPng(fifo); }, {fifo, "not a PNG"});
  // A 100 GB sparse file that starts like a PNG: refused on the limit after 64 MiB.
  const std::string huge = (TempDir() / "huge.png").string();
  {
    std::ofstream out(huge, std::ios::binary | std::ios::trunc);
    out << EncodePng(Image(4, 4));
  }
  fs::resize_file(huge, std::uintmax_t{100} << 30);
  ExpectRefused<std::invalid_argument>([&] { ReadPng(huge); }, {huge, "larger than"});
  fs::remove(huge);
}

TEST(FontBounded, DevZeroFifoAndMissingFileAreRefused) {
  ExpectRefused<EnvironmentError>([] { internal::Font font("/dev/zero"); },
                                  {"/dev/zero", "font file is larger than 33554432 bytes"});
  const std::string fifo = Fifo("font.fifo");
  ExpectRefused<EnvironmentError>([&] { internal::Font font(fifo); }, {fifo, "not a TrueType"});
  const std::string missing = (TempDir() / "missing.ttf").string();
  ExpectRefused<EnvironmentError>([&] { internal::Font font(missing); }, {missing, "not found"});
}

TEST(FontBounded, TheDejaVuFontStillLoads) {
  EXPECT_GT(internal::Font::Regular().Width("topoplan", 12.0f), 10.0f);
}

}  // namespace
}  // namespace render
