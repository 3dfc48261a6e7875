#include "topology/polyline.h"

#include <gtest/gtest.h>

#include <sstream>

#include "base/file_read.h"
#include "base/numbers.h"

namespace topology {
namespace {

std::string ParseError(const std::string& text) {
  std::istringstream in(text);
  try {
    ParseChainCsv(in, "c.csv");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ChainCsvTest, ParsesCommentsBlanksAndSpaces) {
  std::istringstream in("# header\n\n1,2,3\n  4 , 5.5 ,-6e-1  \r\n   # indented comment\n7,8,9\n");
  const Chain c = ParseChainCsv(in, "c.csv");
  ASSERT_EQ(c.cols(), 3);
  EXPECT_EQ(c(1, 1), 5.5);
  EXPECT_EQ(c(2, 1), -0.6);
  std::ostringstream out;
  WriteChainCsv(c, out);
  std::istringstream back(out.str());
  EXPECT_EQ(ParseChainCsv(back, "round-trip"), c);
}

TEST(ChainCsvTest, ErrorsNameFileAndLine) {
  EXPECT_EQ(ParseError("1,2,3\n1,2\n"), "c.csv:2: expected 3 comma-separated numbers x,y,z");
  EXPECT_EQ(ParseError("1,2,3\n\n1,2,3,4\n"), "c.csv:3: expected 3 comma-separated numbers x,y,z");
  EXPECT_EQ(ParseError("1,2,3\n1,x,3\n"), "c.csv:2: 'x' is not a number");
  EXPECT_EQ(ParseError("1,2,3\n1,nan,3\n"), "c.csv:2: non-finite value 'nan'");
  EXPECT_EQ(ParseError("1,2,3\ninf,0,0\n"), "c.csv:2: non-finite value 'inf'");
  EXPECT_EQ(ParseError("1,2,3,\n"), "c.csv:1: trailing comma");
  EXPECT_EQ(ParseError("1,,3\n"), "c.csv:1: '' is not a number");
  EXPECT_EQ(ParseError("# only\n1,2,3\n"), "c.csv: a chain needs at least 2 points, found 1");
  EXPECT_EQ(ParseError(""), "c.csv: a chain needs at least 2 points, found 0");
}

TEST(ChainCsvTest, LimitsAndSubnormals) {
  EXPECT_EQ(ParseError("1,2,3\n1e400,0,0\n"), "c.csv:2: non-finite value '1e400'");
  std::istringstream tiny("1e-310,0,0\n0,0,1\n");
  EXPECT_EQ(ParseChainCsv(tiny, "c.csv")(0, 0), 1e-310);  // subnormal numbers are numbers
  std::string many;
  for (int i = 0; i <= kMaxChainPoints; ++i) many += "0,0,0\n";
  EXPECT_NE(ParseError(many).find("more than 100000 points"), std::string::npos);
  // /dev/zero is refused after kMaxInputFileBytes instead of being read forever.
  try {
    ReadChainCsv("/dev/zero");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/zero: chain file is larger than"),
              std::string::npos);
  }
  EXPECT_EQ(base::ParseFiniteDouble("1e-310"), 1e-310);
  EXPECT_FALSE(base::ParseFiniteDouble("nan"));
  EXPECT_FALSE(base::ParseFiniteDouble("1e400"));
  EXPECT_FALSE(base::ParseFiniteDouble(" 1"));
  EXPECT_FALSE(base::ParseFiniteDouble("1x"));
  EXPECT_FALSE(base::ParseFiniteDouble(""));
}

TEST(ChainCsvTest, MissingFileThrowsWithPath) {
  try {
    ReadChainCsv("/nonexistent/chain.csv");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/chain.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace topology
