// Which topoplan made a file: the version and the git commit of the build, for the provenance of
// reports and pages (generated at build time by cmake/version_info.cmake).
#pragma once

#include <string>

namespace base {

// "0.1.0" (CMake's PROJECT_VERSION).
const char* Version();
// The short git commit the binary was built from, "-dirty" appended when tracked files had
// changes; "unknown" outside a git checkout.
const char* Commit();

}  // namespace base
