#include "app/io.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace app {

void WriteFileAtomic(const std::string& path, const std::string& contents) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const fs::path tmp = target.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error(path + ": cannot write output file");
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw std::runtime_error(path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(path + ": cannot move output into place");
  }
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& flag,
                                    int expected_size) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string field;
  while (std::getline(ss, field, ',')) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(field.c_str(), &end);
    if (field.empty() || end != field.c_str() + field.size() || errno == ERANGE ||
        !std::isfinite(v)) {
      throw std::invalid_argument(flag + ": '" + field + "' is not a finite number");
    }
    values.push_back(v);
  }
  if (!text.empty() && text.back() == ',') throw std::invalid_argument(flag + ": trailing comma");
  if (expected_size >= 0 && static_cast<int>(values.size()) != expected_size) {
    throw std::invalid_argument(flag + ": expected " + std::to_string(expected_size) +
                                " comma-separated numbers, got " + std::to_string(values.size()));
  }
  return values;
}

}  // namespace app
