// app/cli/io.h: checked number lists, output checks, output folders written as a whole, stop checks;
// app/viewer/session.h: script numbers checked when the script is read.
#include "app/cli/io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>

#include "app/viewer/session.h"

namespace app {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("topoplan_io_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string Message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(ParseNumberList, FiniteRangeAndSubnormals) {
  EXPECT_EQ(base::ParseNumberList("1e-310,2", "--x")[0], 1e-310);
  EXPECT_EQ(Message([] { base::ParseNumberList("nan", "--x"); }), "--x: 'nan' is not a finite number");
  EXPECT_EQ(Message([] { base::ParseNumberList("1e400", "--x"); }),
            "--x: '1e400' is not a finite number");
  EXPECT_EQ(Message([] { base::ParseNumberList("1,1e200", "--x", -1, 1e6); }),
            "--x: '1e200' is out of range (|value| <= 1e+06)");
}

TEST(OutputChecks, EmptyUnusableAndFolders) {
  EXPECT_EQ(Message([] { base::CheckOutputDir("", "-o"); }), "-o: empty output path");
  EXPECT_NE(Message([] { base::CheckOutputDir("/dev/null/x", "-o"); }).find("is not a folder"),
            std::string::npos);
  const fs::path d = TempDir("checks");
  EXPECT_EQ(Message([&] { base::CheckOutputDir((d / "new" / "deeper").string(), "-o"); }), "");
  EXPECT_FALSE(fs::exists(d / "new"));  // checking creates nothing
  EXPECT_NE(Message([&] { base::CheckOutputFile(d.string(), "-o"); }).find("is a folder"),
            std::string::npos);
  EXPECT_NE(Message([] { CheckWrithePairs(100001, 100001); }).find("would need 80 GB"),
            std::string::npos);
  EXPECT_EQ(Message([] { CheckWrithePairs(5001, 5001); }), "");
}

// Everything a folder holds apart from the hidden manifest.
std::vector<std::string> Entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename() != ".topoplan-outputs.json") names.push_back(e.path().filename());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(OutputDir, FilesAppearTogetherOrNotAtAll) {
  const fs::path d = TempDir("stage");
  const fs::path out = d / "out";
  {
    OutputDir o(out.string(), "-o", "plan");
    std::ofstream(fs::path(o.staging()) / "a.txt") << "a";
    EXPECT_FALSE(fs::exists(out / "a.txt"));
    // Staged inside the destination (same file system), hidden.
    EXPECT_EQ(fs::path(o.staging()).parent_path(), out);
    EXPECT_EQ(fs::path(o.staging()).filename().string().front(), '.');
    // No Commit: an exception or interrupt leaves nothing behind.
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(fs::is_empty(d));
  {
    OutputDir o(out.string(), "-o", "plan");
    std::ofstream(fs::path(o.staging()) / "a.txt") << "a";
    fs::create_directories(fs::path(o.staging()) / "frames");
    std::ofstream(fs::path(o.staging()) / "frames" / "frame_0099.png") << "old";
    o.Commit();
  }
  EXPECT_EQ(Entries(out), (std::vector<std::string>{"a.txt", "frames"}));
  {  // a re-run replaces that command's outputs as a whole: no stale frames; others stay
    std::ofstream(out / "keep.txt") << "k";
    OutputDir o(out.string(), "-o", "plan");
    std::ofstream(fs::path(o.staging()) / "a.txt") << "b";
    o.Commit();
  }
  std::ifstream a(out / "a.txt");
  std::string text;
  a >> text;
  EXPECT_EQ(text, "b");
  EXPECT_EQ(Entries(out), (std::vector<std::string>{"a.txt", "keep.txt"}));
  {  // another command's outputs live beside them
    OutputDir o(out.string(), "-o", "bench unwrap");
    std::ofstream(fs::path(o.staging()) / "unwrap.csv") << "x";
    o.Commit();
  }
  {
    OutputDir o(out.string(), "-o", "plan");
    std::ofstream(fs::path(o.staging()) / "report.json") << "{}";
    o.Commit();
  }
  EXPECT_EQ(Entries(out), (std::vector<std::string>{"keep.txt", "report.json", "unwrap.csv"}));
  for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename(), "out");
}

TEST(OutputDir, RefusesFoldersOfOtherFilesAndCleansStaleStaging) {
  const fs::path d = TempDir("foreign");
  std::ofstream(d / "thesis.tex") << "mine";
  EXPECT_NE(Message([&] { OutputDir o(d.string(), "-o", "plan"); })
                .find("holds files topoplan did not write ('thesis.tex'"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(d / "thesis.tex"));
  // An empty folder is fine; a staging folder of a process that no longer runs is removed.
  const fs::path e = TempDir("stale");
  fs::create_directories(e / ".topoplan-staging-999999999");
  {
    OutputDir o(e.string(), "-o", "plan");
    o.Commit();
  }
  EXPECT_FALSE(fs::exists(e / ".topoplan-staging-999999999"));
}

TEST(StopCheck, TimeoutAndSignal) {
  {
    const StopCheck none(0.0);
    EXPECT_NO_THROW(none.Poll());
    const StopCheck inner(1e-9);  // nested: the earliest deadline wins
    try {
      inner.Poll();
      FAIL();
    } catch (const StopRequested& e) {
      EXPECT_TRUE(e.timeout);
    }
  }
  const StopCheck stop(0.0);
  std::raise(SIGINT);  // only sets the flag while a StopCheck lives
  try {
    stop.Poll();
    FAIL();
  } catch (const StopRequested& e) {
    EXPECT_FALSE(e.timeout);
  }
}

TEST(ParseScript, NumbersAreCheckedWhenRead) {
  const fs::path d = TempDir("script");
  const auto parse = [&](const std::string& text) {
    std::ofstream(d / "s.txt") << text;
    return Message([&] { ParseScript((d / "s.txt").string()); });
  };
  EXPECT_EQ(parse("frames 3\nseed 7\ncamera 10 20 3\n"), "");
  EXPECT_NE(parse("frames nan\n").find(":1: 'nan' is not a finite number"), std::string::npos);
  EXPECT_NE(parse("frames 1e10\n").find("out of range"), std::string::npos);
  EXPECT_NE(parse("frames 2.5\n").find("not an integer"), std::string::npos);
  std::string many;
  for (int i = 0; i < 11; ++i) many += "frames 100000\n";
  EXPECT_NE(parse(many).find("frames in the script (limit)"), std::string::npos);
  EXPECT_NE(parse("seed -1\n").find("out of range"), std::string::npos);
  EXPECT_NE(Message([] { ParseScript("/dev/zero"); }).find("script file is larger than"),
            std::string::npos);
}

// A folder holding only the journal of a hard-killed run (no manifest yet) is accepted again, so
// that the run can resume there; Commit leaves the journal alone.
TEST(OutputDir, AcceptsTheJournalOfAKilledRun) {
  const fs::path d = TempDir("journal");
  std::string journal;
  {
    OutputDir o(d.string(), "-o", "bench grasp");
    journal = o.JournalPath("bench-grasp");
    std::ofstream(journal) << "# topoplan journal 1: x\n";
  }  // killed: no Commit
  EXPECT_EQ(fs::path(journal).parent_path(), d);
  EXPECT_TRUE(fs::exists(journal));
  {
    OutputDir o(d.string(), "-o", "bench grasp");
    std::ofstream(fs::path(o.staging()) / "grasp.csv") << "rows";
    o.Commit();
  }
  EXPECT_TRUE(fs::exists(journal));
  EXPECT_TRUE(fs::exists(d / "grasp.csv"));
}

}  // namespace
}  // namespace app
