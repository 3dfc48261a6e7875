#include "topology/input_limits.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace topology {

std::string ReadFileBounded(const std::string& path, const std::string& what,
                            std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot open " + what + " file");
  std::string out;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof(buffer));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (out.size() + got > max_bytes) {
      throw std::invalid_argument(path + ": " + what + " file is larger than " +
                                  std::to_string(max_bytes) + " bytes (limit)");
    }
    out.append(buffer, got);
  }
  if (in.bad()) throw std::invalid_argument(path + ": cannot read " + what + " file");
  return out;
}

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

}  // namespace topology
