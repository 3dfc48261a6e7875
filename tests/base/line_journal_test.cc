// base/line_journal: records survive reopening, a torn last line (a kill in the middle of a
// write) is dropped and cut off, a damaged line before intact ones and another configuration are
// refused with the file named.
#include "base/line_journal.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "base/file_read.h"

namespace base {
namespace {

namespace fs = std::filesystem;

class LineJournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("line_journal_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / "journal").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  void AppendRaw(const std::string& bytes) {
    std::ofstream out(path_, std::ios::app | std::ios::binary);
    out << bytes;
  }
  std::string Error(const std::string& config) {
    try {
      LineJournal j(path_, config);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(opened)";
  }
  fs::path dir_;
  std::string path_;
};

TEST_F(LineJournalTest, FnvOfKnownStrings) {
  EXPECT_EQ(Fnv1a64(""), 14695981039346656037ull);
  EXPECT_EQ(Fnv1a64("a"), 0xaf63dc4c8601ec8cull);  // published FNV-1a 64 test vector
}

TEST_F(LineJournalTest, RecordsSurviveReopening) {
  {
    LineJournal j(path_, "seed=0");
    EXPECT_TRUE(j.records().empty());
    j.Append("a,1,2");
    j.Append("b,3,4");
  }
  LineJournal j(path_, "seed=0");
  ASSERT_EQ(j.records().size(), 2u);
  EXPECT_EQ(j.records()[0], "a,1,2");
  EXPECT_EQ(j.records()[1], "b,3,4");
  EXPECT_FALSE(j.dropped_torn_line());
  j.Append("c");
  LineJournal k(path_, "seed=0");
  EXPECT_EQ(k.records().size(), 3u);
}

TEST_F(LineJournalTest, TornLastLineIsDroppedAndCutOff) {
  {
    LineJournal j(path_, "cfg");
    j.Append("first");
    j.Append("second");
  }
  const std::string intact = ReadFileBounded(path_, "test");
  AppendRaw("thi");  // a write cut short: no newline
  {
    LineJournal j(path_, "cfg");
    EXPECT_TRUE(j.dropped_torn_line());
    EXPECT_EQ(j.records().size(), 2u);
    EXPECT_EQ(ReadFileBounded(path_, "test"), intact);  // cut back to the intact records
    j.Append("third");
  }
  LineJournal j(path_, "cfg");
  ASSERT_EQ(j.records().size(), 3u);
  EXPECT_EQ(j.records()[2], "third");
}

TEST_F(LineJournalTest, LastLineWithWrongChecksumIsDropped) {
  {
    LineJournal j(path_, "cfg");
    j.Append("first");
  }
  AppendRaw(std::string("\0\0\0second\t0000000000000000\n",
                        27));  // garbage with a newline (zeroed block)
  LineJournal j(path_, "cfg");
  EXPECT_TRUE(j.dropped_torn_line());
  ASSERT_EQ(j.records().size(), 1u);
  EXPECT_EQ(j.records()[0], "first");
}

TEST_F(LineJournalTest, DamagedLineBeforeIntactOnesIsRefused) {
  {
    LineJournal j(path_, "cfg");
    j.Append("first");
  }
  AppendRaw("edited\t0123456789abcdef\n");
  {
    std::ostringstream good;
    good << "third\t";
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(Fnv1a64("third")));
    good << hex << "\n";
    AppendRaw(good.str());
  }
  const std::string message = Error("cfg");
  EXPECT_NE(message.find(path_ + ":3: damaged record"), std::string::npos) << message;
}

TEST_F(LineJournalTest, OtherConfigurationIsRefused) {
  {
    LineJournal j(path_, "seed=0");
    j.Append("x");
  }
  const std::string message = Error("seed=1");
  EXPECT_NE(message.find("another configuration (journal: 'seed=0'; this run: 'seed=1')"),
            std::string::npos)
      << message;
  EXPECT_EQ(LineJournal(path_, "seed=0").records().size(), 1u);  // left as it was
  // Only the words that differ are named; another word count names both in full.
  EXPECT_NE(Error("seed=0 x").find("(journal: 'seed=0'; this run: 'seed=0 x')"), std::string::npos);
  {
    fs::remove(path_);
    LineJournal j(path_, "a=1 b=2 c=3");
  }
  EXPECT_NE(Error("a=1 b=5 c=3").find("(journal: 'b=2'; this run: 'b=5')"), std::string::npos);
}

TEST_F(LineJournalTest, TornHeaderStartsAfreshAndForeignFileIsRefused) {
  AppendRaw("# topoplan jour");  // killed while writing the header
  {
    LineJournal j(path_, "cfg");
    EXPECT_TRUE(j.records().empty());
    j.Append("r");
  }
  EXPECT_EQ(LineJournal(path_, "cfg").records().size(), 1u);
  fs::remove(path_);
  AppendRaw("grasp,object\n");
  EXPECT_NE(Error("cfg").find("not a topoplan journal"), std::string::npos);
}

TEST_F(LineJournalTest, RecordsWithNewlineOrTabAreRefusedAndRemoveDeletes) {
  LineJournal j(path_, "cfg");
  EXPECT_THROW(j.Append("a\nb"), std::invalid_argument);
  EXPECT_THROW(j.Append("a\tb"), std::invalid_argument);
  j.Remove();
  EXPECT_FALSE(fs::exists(path_));
}

}  // namespace
}  // namespace base
