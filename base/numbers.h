// Numbers in text: the one parser for text fields, flags and lists of numbers, and the one printer
// of numbers into text that users read back. Both are locale-independent: a program that has set
// a comma-decimal locale (setlocale(LC_ALL, "de_DE.UTF-8"), Python's locale.setlocale) reads and
// writes the same files as the command line ("0.5", never "0,5").
#pragma once

#include <clocale>
#include <locale.h>

#include <optional>
#include <string>
#include <vector>

namespace base {

// What a piece of text is as a number.
enum class NumberKind {
  kFinite,     // a finite double (subnormals such as 1e-310 included)
  kNonFinite,  // a whole number token that is not finite: nan, inf, 1e400
  kNotANumber  // anything else: empty, leading or trailing spaces or characters
};

// The whole of `text` as a double, in the C locale's decimal syntax (strtod: decimal point '.',
// exponents, a leading sign; hex floats such as "0x1p3" are kNotANumber). *value is set for
// kFinite.
NumberKind ClassifyNumber(const std::string& text, double* value = nullptr);

// The whole of `text` as a finite double (ClassifyNumber == kFinite), else std::nullopt.
std::optional<double> ParseFiniteDouble(const std::string& text);

// The whole of `text` as a decimal integer: an optional sign and the digits 0-9 only (no
// spaces, no "0x", no fraction, no exponent); leading zeros are decimal ("010" is 10, never
// octal). std::nullopt when it is not one or does not fit a long long.
std::optional<long long> ParseInteger(const std::string& text);

// Parses "v1,v2,...,vn" into doubles. Throws std::invalid_argument naming `flag` when a field is
// not a finite number (ParseFiniteDouble: 1e-310 is one, nan/inf/1e400 are not), when
// |value| > max_abs or, if expected_size >= 0, when the count differs.
std::vector<double> ParseNumberList(const std::string& text, const std::string& flag,
                                    int expected_size = -1, double max_abs = 1e300);

// `v` with `digits` digits after the decimal point ('.' whatever the locale), e.g.
// FormatFixed(59874.780477836466, 1) == "59874.8"; "nan"/"inf"/"-inf" for non-finite values.
std::string FormatFixed(double v, int digits);
// The shortest text that reads back as exactly `v` ("0.1", "1e-07"), locale-independent.
std::string FormatShortest(double v);

// While alive, the C library's number formatting and parsing on this thread (printf, strtod,
// and what third-party parsers call) use the "C" locale, whatever setlocale() chose for the
// process; the thread's previous locale comes back on destruction. For entry points called from
// programs that may have set another locale (the Python module wraps every call in one).
class ScopedClassicLocale {
 public:
  ScopedClassicLocale();
  ~ScopedClassicLocale();
  ScopedClassicLocale(const ScopedClassicLocale&) = delete;
  ScopedClassicLocale& operator=(const ScopedClassicLocale&) = delete;

 private:
  locale_t previous_;
};

}  // namespace base
