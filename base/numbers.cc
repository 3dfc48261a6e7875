#include "base/numbers.h"

#include <stdlib.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace base {
namespace {

// The "C" locale as an object, for strtod_l (made once; never freed).
locale_t ClassicLocale() {
  static const locale_t c = newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
  return c;
}

}  // namespace

NumberKind ClassifyNumber(const std::string& text, double* value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) {
    return NumberKind::kNotANumber;
  }
  // Decimal only: strtod also reads C99 hex floats ("0x21c" = 540, "0x1p3" = 8), which nobody
  // writes in a flag or a CSV field on purpose and JSON does not allow.
  const size_t digits = (text[0] == '+' || text[0] == '-') ? 1 : 0;
  if (text.size() >= digits + 2 && text[digits] == '0' &&
      (text[digits + 1] == 'x' || text[digits + 1] == 'X')) {
    return NumberKind::kNotANumber;
  }
  // Fast path: std::from_chars (correctly rounded, as strtod; no locale), taken only when it reads
  // the whole text as a finite number. Everything else (a leading '+', inf/nan,
  // overflow, underflow to zero, garbage) goes to strtod below, which decides as it always has.
  double fast = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), fast);
  if (ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(fast)) {
    if (value != nullptr) *value = fast;
    return NumberKind::kFinite;
  }
  char* end = nullptr;
  errno = 0;
  const double v = strtod_l(text.c_str(), &end, ClassicLocale());
  if (end != text.c_str() + text.size()) return NumberKind::kNotANumber;
  // ERANGE also reports underflow to a subnormal or zero (1e-310), which is a number.
  if (!std::isfinite(v) || (errno == ERANGE && std::fabs(v) >= 1.0)) return NumberKind::kNonFinite;
  if (value != nullptr) *value = v;
  return NumberKind::kFinite;
}

std::optional<double> ParseFiniteDouble(const std::string& text) {
  double v = 0.0;
  if (ClassifyNumber(text, &v) != NumberKind::kFinite) return std::nullopt;
  return v;
}

std::optional<long long> ParseInteger(const std::string& text) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;  // from_chars takes '-' but not '+'
  if (first == last || !(*first == '-' || (*first >= '0' && *first <= '9'))) return std::nullopt;
  long long v = 0;
  const auto [ptr, ec] = std::from_chars(first, last, v, 10);
  if (ec != std::errc() || ptr != last) return std::nullopt;
  return v;
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& flag,
                                    int expected_size, double max_abs) {
  std::vector<double> values;
  std::stringstream ss(text);
  ss.imbue(std::locale::classic());  // "0.5" whatever the global locale
  std::string field;
  while (std::getline(ss, field, ',')) {
    const std::optional<double> v = ParseFiniteDouble(field);
    if (!v) throw std::invalid_argument(flag + ": '" + field + "' is not a finite number");
    if (std::fabs(*v) > max_abs) {
      throw std::invalid_argument(flag + ": '" + field +
                                  "' is out of range (|value| <= " + FormatShortest(max_abs) + ")");
    }
    values.push_back(*v);
  }
  if (!text.empty() && text.back() == ',') throw std::invalid_argument(flag + ": trailing comma");
  if (expected_size >= 0 && static_cast<int>(values.size()) != expected_size) {
    throw std::invalid_argument(flag + ": expected " + std::to_string(expected_size) +
                                " comma-separated numbers, got " + std::to_string(values.size()));
  }
  return values;
}

std::string FormatFixed(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::array<char, 400> buf{};
  const auto [ptr, ec] =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::fixed, digits);
  if (ec != std::errc()) return FormatShortest(v);
  return std::string(buf.data(), ptr);
}

std::string FormatShortest(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::array<char, 64> buf{};
  const auto [ptr, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return ec == std::errc() ? std::string(buf.data(), ptr) : std::string("?");
}

ScopedClassicLocale::ScopedClassicLocale() : previous_(uselocale(ClassicLocale())) {}

ScopedClassicLocale::~ScopedClassicLocale() { uselocale(previous_); }

}  // namespace base
