// base/file_read: the bounded reader with hostile files (a named pipe nobody writes to, a
// huge sparse file, a folder, /dev/zero): each is answered at once, never read without end.
#include "base/file_read.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "base/json_reader.h"

namespace base {
namespace {

namespace fs = std::filesystem;

std::string Message(const std::string& path, std::size_t max_bytes = base::kMaxInputFileBytes) {
  try {
    base::ReadFileBounded(path, "test", max_bytes);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(read)";
}

TEST(ReadFileBounded, HostileFilesAreAnsweredAtOnce) {
  const fs::path dir = fs::temp_directory_path() / ("topoplan-limits-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const auto start = std::chrono::steady_clock::now();
  // A named pipe nobody writes to is answered at once instead of blocking in open(), and said to
  // be one (its empty text would otherwise be reported as a malformed file).
  const std::string fifo = (dir / "pipe").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(Message(fifo),
            fifo + ": test file is a named pipe that gave no data (nothing wrote to it)");
  // A 100 GB sparse file is refused on its size, without reading.
  const std::string huge = (dir / "huge").string();
  std::ofstream(huge).close();
  fs::resize_file(huge, std::uintmax_t{100} << 30);
  EXPECT_EQ(Message(huge), huge + ": test file is larger than 67108864 bytes (limit)");
  EXPECT_EQ(Message(dir.string()), dir.string() + ": cannot open test file (it is a folder)");
  EXPECT_EQ(Message("/dev/zero", 1000), "/dev/zero: test file is larger than 1000 bytes (limit)");
  EXPECT_EQ(Message((dir / "missing").string()),
            (dir / "missing").string() + ": cannot open test file");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  // Exactly the limit is read; one byte more is refused.
  const std::string small = (dir / "small").string();
  std::ofstream(small) << "12345";
  EXPECT_EQ(base::ReadFileBounded(small, "test", 5), "12345");
  EXPECT_EQ(Message(small, 4), small + ": test file is larger than 4 bytes (limit)");
  fs::remove_all(dir);
}

TEST(ReadFileLimited, ReadsAWholeSmallFile) {
  const fs::path dir = fs::temp_directory_path() / ("topoplan-limited-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "small.txt").string();
  std::ofstream(path) << "hello";
  const FileBytes file = ReadFileLimited(path, 100);
  EXPECT_EQ(file.status, ReadStatus::kOk);
  EXPECT_EQ(file.bytes, "hello");
  EXPECT_EQ(ReadFileLimited(path, 5).status, ReadStatus::kOk);  // exactly at the limit
  EXPECT_EQ(ReadFileLimited(path, 4).status, ReadStatus::kTooLarge);
  EXPECT_EQ(ReadFileLimited((dir / "nope").string(), 100).status, ReadStatus::kCannotOpen);
  EXPECT_EQ(ReadFileLimited(dir.string(), 100).status, ReadStatus::kIsFolder);
  fs::remove_all(dir);
}

TEST(ReadFileLimited, DevZeroStopsJustPastTheLimit) {
  const FileBytes file = ReadFileLimited("/dev/zero", 1000);
  EXPECT_EQ(file.status, ReadStatus::kTooLarge);
  EXPECT_TRUE(file.bytes.empty());
}

TEST(ReadFileLimited, PipeWithoutWriterReadsAsEmpty) {
  const fs::path fifo =
      fs::temp_directory_path() / ("topoplan-limited-" + std::to_string(getpid()) + ".fifo");
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const FileBytes file = ReadFileLimited(fifo.string(), 100);
  EXPECT_EQ(file.status, ReadStatus::kOk);
  EXPECT_TRUE(file.bytes.empty());
  fs::remove(fifo);
}

// PrefixErrors: the context is added once; a message located at or below the same place by an
// inner PrefixErrors keeps its one location.
TEST(PrefixErrors, SaysEachLocationOnce) {
  const auto inner = [] {
    base::PrefixErrors("f.json: tasks[0].feature.chain",
                       [] { throw std::invalid_argument("no chain named 'x'"); });
  };
  try {
    base::PrefixErrors("f.json: tasks[0].feature", inner);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "f.json: tasks[0].feature.chain: no chain named 'x'");
  }
  try {
    base::PrefixErrors("--robot", [] { throw std::invalid_argument("cannot open"); });
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--robot: cannot open");
  }
}

// A NUL byte ends the text for the JSON parser: the reader refuses it, naming the file and the
// byte offset, instead of ignoring what follows it.
TEST(ParseJsonText, RefusesANulByte) {
  const std::string text = std::string("{\"name\": \"a\"}") + '\0' + "garbage";
  try {
    base::ParseJsonText(text, "g.json");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "g.json: invalid JSON: a NUL byte at byte offset 13 (JSON text holds none)");
  }
  const fs::path file = fs::temp_directory_path() / ("nul_" + std::to_string(::getpid()) + ".json");
  std::ofstream(file, std::ios::binary) << text;
  EXPECT_THROW(base::ParseJsonFile(file.string(), "test"), std::invalid_argument);
  fs::remove(file);
}

}  // namespace
}  // namespace base
