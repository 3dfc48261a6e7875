#include "app/assets.h"

#include <cstdlib>
#include <filesystem>

#include "app/command.h"

namespace app {

std::string AssetRoot() {
  if (const char* env = std::getenv("TOPOPLAN_ASSETS"); env != nullptr && *env != '\0') return env;
  return TOPOPLAN_ASSET_DIR;
}

std::string AssetPath(const std::string& relative) {
  const std::filesystem::path p = std::filesystem::path(AssetRoot()) / relative;
  if (!std::filesystem::exists(p)) {
    throw EnvironmentError("missing asset " + p.string() +
                           " (set TOPOPLAN_ASSETS to the repository's assets/ folder)");
  }
  return p.string();
}

}  // namespace app
