// Where package://NAME/REL and file:// mesh URIs of a URDF point to (ROS's package lookup, with
// package.xml names, without a ROS installation). Internal to planning/robot (robot_io.cc).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace planning::internal {

// The <name> of the ROS package manifest (package.xml) in `dir`; "" when there is none, it is
// unreadable or larger than 1 MiB.
std::string PackageXmlName(const std::filesystem::path& dir);

// Resolves mesh URIs: package://NAME/REL, file://PATH and paths relative to the URDF's folder.
// The folder of package NAME is, in this order (as ROS finds packages):
//   for each search root R: R itself when its folder name is NAME or its package.xml names NAME,
//   R/NAME, and folders below R (up to 3 levels, not hidden) whose package.xml names NAME;
//   then the URDF's folder and its ancestors A: A when its name is NAME or its package.xml names
//   NAME, and A/NAME.
// REL may not leave the package (no ".." above it); symbolic links inside are followed.
// Resolve throws std::invalid_argument "<source>: ..." naming the URI and what was tried.
struct MeshResolver {
  std::string source;                      // the URDF, for messages
  std::filesystem::path base_dir;          // the URDF's folder
  std::vector<std::string> package_paths;  // search roots, in order
  // Package name → candidate roots, filled on first use.
  mutable std::map<std::string, std::vector<std::filesystem::path>> found;

  std::string Resolve(const std::string& uri) const;
  const std::vector<std::filesystem::path>& PackageRoots(const std::string& pkg) const;
};

}  // namespace planning::internal
