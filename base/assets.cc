#include "base/assets.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

#include "base/errors.h"

namespace base {

std::string AssetRoot() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("TOPOPLAN_ASSETS"); env != nullptr && *env != '\0') return env;
  // Installed: <prefix>/bin/topoplan with its data in <prefix>/share/topoplan (the relative path
  // comes from the install layout, cmake/TopoplanInstall.cmake). The executable does not move
  // while it runs, so this is looked up once.
  static const std::string installed = [] {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return std::string();
    const fs::path dir = (exe.parent_path() / TOPOPLAN_INSTALLED_ASSET_DIR).lexically_normal();
    return fs::is_directory(dir, ec) ? dir.string() : std::string();
  }();
  if (!installed.empty()) return installed;
  // Not installed (a binary in the build tree): the source tree's assets/ folder.
  return TOPOPLAN_ASSET_DIR;
}

std::string AssetPath(const std::string& relative) {
  const std::filesystem::path p = std::filesystem::path(AssetRoot()) / relative;
  if (!std::filesystem::exists(p)) {
    throw EnvironmentError(
        "missing asset " + p.string() +
        " (set TOPOPLAN_ASSETS to an assets/ folder: the repository's, or PREFIX/share/topoplan of "
        "an installation)");
  }
  return p.string();
}

std::string ResolveScenarioPath(const std::string& arg, const std::string& what) {
  namespace fs = std::filesystem;
  if (fs::exists(arg)) return arg;
  if (arg.find('/') == std::string::npos) {
    const bool has_ext = arg.size() > 5 && arg.substr(arg.size() - 5) == ".json";
    const fs::path p = fs::path(AssetRoot()) / "scenarios" / (has_ext ? arg : arg + ".json");
    if (fs::exists(p)) return p.string();
  }
  throw std::invalid_argument(what + ": no file '" + arg +
                              "' and no scenario of that name in assets/scenarios/");
}

}  // namespace base
