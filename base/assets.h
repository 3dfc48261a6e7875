// Locating the installed data under assets/.
#pragma once

#include <memory>
#include <string>

namespace base {

// Root of the asset tree: $TOPOPLAN_ASSETS if set (then the only place looked in), else
// <exe dir>/../share/topoplan when it exists (an installed binary), else the source tree's assets/
// baked in at build time (a binary run from the build tree).
std::string AssetRoot();

// AssetRoot()/relative; throws EnvironmentError (exit 3) when the file does not exist.
std::string AssetPath(const std::string& relative);

// A scenario argument: an existing file path as given, or a bare name ("unwrap") looked up as
// assets/scenarios/NAME.json. Throws std::invalid_argument naming the argument otherwise, its
// message led by `what` (the argument's name, e.g. "--scenario").
std::string ResolveScenarioPath(const std::string& arg, const std::string& what = "SCENARIO");

}  // namespace base
