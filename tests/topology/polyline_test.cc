#include "topology/polyline.h"

#include <gtest/gtest.h>

#include <sstream>

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
