// base/numbers.h: ClassifyNumber's from_chars fast path gives exactly strtod's answer.
#include "base/numbers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

namespace base {
namespace {

// The reference: strtod as ClassifyNumber used it before the fast path (C locale in tests),
// decimal only.
NumberKind Reference(const std::string& text, double* value) {
  if (text.empty() || text[0] == ' ' || text[0] == '\t' || text[0] == '\n' ||
      text.find_first_of("xX") != std::string::npos) {
    return NumberKind::kNotANumber;
  }
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return NumberKind::kNotANumber;
  if (!std::isfinite(v) || (errno == ERANGE && std::fabs(v) >= 1.0)) return NumberKind::kNonFinite;
  *value = v;
  return NumberKind::kFinite;
}

void ExpectSame(const std::string& text) {
  double got = -1.0, want = -2.0;
  const NumberKind k = ClassifyNumber(text, &got);
  const NumberKind r = Reference(text, &want);
  ASSERT_EQ(static_cast<int>(k), static_cast<int>(r)) << "'" << text << "'";
  if (k == NumberKind::kFinite) {
    EXPECT_EQ(std::memcmp(&got, &want, sizeof got), 0) << "'" << text << "'";
  }
}

TEST(ClassifyNumber, AgreesWithStrtodBitForBit) {
  for (const char* t : {"0",
                        "-0",
                        "+0",
                        "1",
                        "+1.5",
                        "-2.5e-3",
                        ".5",
                        "5.",
                        "1e-310",
                        "4.9e-324",
                        "1e-400",
                        "1e308",
                        "1.7976931348623157e308",
                        "1.8e308",
                        "1e400",
                        "-1e400",
                        "inf",
                        "-inf",
                        "nan",
                        "NaN",
                        "0x1p3",
                        "0X1.8P1",
                        "-0x1p3",
                        "+0x21c",
                        "0x",
                        "1,5",
                        "1.5 ",
                        " 1.5",
                        "",
                        "-",
                        "+",
                        "e5",
                        "1e",
                        "1e+",
                        "--1",
                        "0.1.2",
                        "1_000",
                        "٣",
                        "2.7000000000000002",
                        "0.0084821885429869071",
                        "00012",
                        "-.0"}) {
    ExpectSame(t);
  }
  std::mt19937_64 rng(38);
  std::uniform_int_distribution<int> exponent(-330, 310);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  char buf[64];
  for (int i = 0; i < 20000; ++i) {
    const double v = mantissa(rng) * std::pow(10.0, exponent(rng));
    for (const char* fmt : {"%.17g", "%.6g", "%.3e", "%.20f"}) {
      std::snprintf(buf, sizeof buf, fmt, v);
      ExpectSame(buf);
    }
  }
}

// strtod reads C99 hex floats; a flag or a CSV field is decimal ("--angles 0x21c" is refused,
// not read as 540).
TEST(ClassifyNumber, HexFloatsAreNotNumbers) {
  for (const char* t : {"0x21c", "0X21C", "-0x1p3", "+0x1.8p1", "0x0"}) {
    double v = -1.0;
    EXPECT_EQ(ClassifyNumber(t, &v), NumberKind::kNotANumber) << t;
    EXPECT_EQ(v, -1.0) << t;
    EXPECT_FALSE(ParseFiniteDouble(t).has_value()) << t;
  }
  EXPECT_EQ(ClassifyNumber("0"), NumberKind::kFinite);
  EXPECT_EQ(ClassifyNumber("-0.5e1"), NumberKind::kFinite);
}

}  // namespace
}  // namespace base
