// Numbers in text: the one parser for text fields, flags and lists of numbers.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace base {

// The whole of `text` as a finite double (strtod syntax; leading/trailing spaces not allowed).
// Subnormal values such as 1e-310 are numbers; "nan", "inf", overflow (1e400), empty text and
// trailing characters give std::nullopt.
std::optional<double> ParseFiniteDouble(const std::string& text);

// Parses "v1,v2,...,vn" into doubles. Throws std::invalid_argument naming `flag` when a field is
// not a finite number (ParseFiniteDouble: 1e-310 is one, nan/inf/1e400 are not), when
// |value| > max_abs or, if expected_size >= 0, when the count differs.
std::vector<double> ParseNumberList(const std::string& text, const std::string& flag,
                                    int expected_size = -1, double max_abs = 1e300);

}  // namespace base
