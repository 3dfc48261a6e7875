// A folder of robots as users bring them (a ROS workspace, a robot-description collection): every
// URDF below it, paired with its SRDF, loaded and checked in each SRDF reference pose
// (group_state). What `topoplan robots check DIR` prints.
//
//   const std::vector<CollectionRobot> robots = FindCollectionRobots("ws/src");
//   for (const CollectionRobot& r : robots) {
//     const CollectionRow row = CheckCollectionRobot(r, options);  // never throws on bad robots
//   }
//
// Pairing: an SRDF goes with the URDF of the same package (the nearest folder above the file
// with a package.xml, else the first folder below DIR) and the same file stem (robot.srdf with
// robot.urdf); failing that, with the package's URDF whose <robot name> is the SRDF's. URDFs
// without an SRDF are rows of their own (loaded, no poses); an SRDF without a URDF is a row
// with status kNoUrdf.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "base/enum_names.h"

namespace planning {

struct CollectionRobot {
  std::string urdf;       // "" for an SRDF without URDF
  std::string srdf;       // "" when none pairs with the URDF
  std::string package;    // folder the pairing looked in (the package root), for display
  std::string paired_by;  // "stem", "robot name" or ""
};

// Every *.urdf and *.srdf file below `dir` (symbolic links followed, at most 12 levels, hidden
// folders skipped), paired as above; sorted by path, deterministic. Throws std::invalid_argument
// when `dir` is not a readable folder.
std::vector<CollectionRobot> FindCollectionRobots(const std::string& dir);

struct CollectionOptions {
  std::vector<std::string> package_paths;  // package:// roots tried first
  int max_pairs = 20;                      // colliding pairs listed per pose
  bool exact_meshes = false;               // CollisionOptions::exact_meshes (no hull first test)
};

// One SRDF reference pose checked: yes/no collision queries, as `check --pose`.
struct CollectionPose {
  std::string name, group;
  bool in_collision = false;
  std::vector<std::string> pairs;      // "link_a vs link_b" of the colliding pairs
  std::vector<std::string> hull_only;  // pairs whose convex hulls overlap, meshes do not
  std::vector<std::string> warnings;   // e.g. a value outside the joint limits (checked anyway)
  std::string error;                   // the pose could not be applied (then not checked)
  double check_seconds = 0.0;          // forward kinematics + collision check
};

enum class CollectionStatus { kLoaded, kRefused, kNoUrdf };
inline constexpr base::EnumName<CollectionStatus> kCollectionStatusNames[] = {
    {CollectionStatus::kLoaded, "loaded"},
    {CollectionStatus::kRefused, "refused"},
    {CollectionStatus::kNoUrdf, "no-urdf"}};
constexpr std::span<const base::EnumName<CollectionStatus>> EnumNames(CollectionStatus) {
  return kCollectionStatusNames;
}

struct CollectionRow {
  CollectionRobot robot;
  CollectionStatus status = CollectionStatus::kRefused;
  std::string reason;  // kRefused: the loader's message
  std::string name;    // <robot name>
  int links = 0, dofs = 0, meshes = 0;
  std::string base = "fixed";         // fixed, floating or planar
  std::vector<std::string> warnings;  // the loader's and the SRDF's
  std::vector<CollectionPose> poses;  // one per group_state of the SRDF, in file order
  double load_seconds = 0.0;          // URDF + meshes + SRDF + collision set-up
};

// Loads and checks one robot; failures are rows (status kRefused, reason), not exceptions.
CollectionRow CheckCollectionRobot(const CollectionRobot& robot, const CollectionOptions& options);

}  // namespace planning
