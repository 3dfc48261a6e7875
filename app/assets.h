// Locating the installed data under assets/.
#pragma once

#include <string>

namespace app {

// Root of the asset tree: $TOPOPLAN_ASSETS if set, else the source tree's assets/ folder baked in
// at build time.
std::string AssetRoot();

// AssetRoot()/relative; throws EnvironmentError (exit 3) when the file does not exist.
std::string AssetPath(const std::string& relative);

}  // namespace app
