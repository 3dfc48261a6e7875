// Helpers shared by the fuzz targets (fuzz_targets.h).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tests/fuzz/fuzz_targets.h"

namespace topoplan_fuzz {

std::string WriteInput(const uint8_t* data, size_t size, const std::string& name) {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("topoplan-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string path = (dir / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error(path + ": cannot write the fuzz input");
  return path;
}

void Rejected(const std::exception& e) {
  static const bool verbose = std::getenv("TOPOPLAN_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "  refused: %s\n", e.what());
}

std::string AssetPath(const std::string& relative) {
  return std::string(TOPOPLAN_SOURCE_DIR) + "/assets/" + relative;
}

}  // namespace topoplan_fuzz
