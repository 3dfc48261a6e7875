#include "base/numbers.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace base {

std::optional<double> ParseFiniteDouble(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
  // ERANGE also reports underflow to a subnormal or zero (1e-310), which is a number.
  if (errno == ERANGE && std::fabs(v) >= 1.0) return std::nullopt;
  return v;
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& flag,
                                    int expected_size, double max_abs) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string field;
  while (std::getline(ss, field, ',')) {
    const std::optional<double> v = base::ParseFiniteDouble(field);
    if (!v) throw std::invalid_argument(flag + ": '" + field + "' is not a finite number");
    if (std::fabs(*v) > max_abs) {
      std::ostringstream limit;
      limit << max_abs;
      throw std::invalid_argument(flag + ": '" + field +
                                  "' is out of range (|value| <= " + limit.str() + ")");
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

}  // namespace base
