// Walking a folder of robots: pairing URDFs with SRDFs, loading and checking each reference pose.
#include "planning/motion/robot_collection.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <iterator>
#include <map>
#include <stdexcept>
#include <system_error>

#include "base/file_read.h"
#include "planning/collision/collision.h"
#include "planning/motion/robot_scene.h"
#include "planning/robot/kinematics.h"

namespace planning {
namespace {

namespace fs = std::filesystem;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::string LowerExt(const fs::path& p) {
  std::string e = p.extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// The name="..." of the first <robot ...> element (comments skipped); "" when there is none or
// the file cannot be read. Enough for pairing; the loaders validate the file.
std::string XmlRobotName(const fs::path& file) {
  const base::FileBytes f = base::ReadFileLimited(file.string(), std::size_t{64} << 20);
  if (f.status != base::ReadStatus::kOk) return "";
  const std::string& x = f.bytes;
  size_t i = 0;
  while ((i = x.find('<', i)) != std::string::npos) {
    if (x.compare(i, 4, "<!--") == 0) {
      i = x.find("-->", i + 4);
      if (i == std::string::npos) return "";
      continue;
    }
    if (x.compare(i, 6, "<robot") == 0 && i + 6 < x.size() &&
        (std::isspace(static_cast<unsigned char>(x[i + 6])) || x[i + 6] == '>')) {
      const size_t end = x.find('>', i);
      const std::string tag = x.substr(i, end == std::string::npos ? std::string::npos : end - i);
      for (size_t a = tag.find("name"); a != std::string::npos; a = tag.find("name", a + 4)) {
        if (a == 0 || !std::isspace(static_cast<unsigned char>(tag[a - 1]))) continue;
        size_t k = a + 4;
        while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
        if (k >= tag.size() || tag[k] != '=') continue;
        ++k;
        while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
        if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) continue;
        const size_t close = tag.find(tag[k], k + 1);
        if (close == std::string::npos) return "";
        return tag.substr(k + 1, close - k - 1);
      }
      return "";
    }
    ++i;
  }
  return "";
}

// The package a file belongs to: the nearest folder above it (up to `root`) holding a
// package.xml, else the first folder below `root` on its path, else `root`.
fs::path PackageOf(const fs::path& file, const fs::path& root) {
  std::error_code ec;
  for (fs::path d = file.parent_path(); !d.empty(); d = d.parent_path()) {
    if (fs::is_regular_file(d / "package.xml", ec)) return d;
    if (d == root || d == d.parent_path()) break;
  }
  const fs::path rel = file.lexically_relative(root);
  if (!rel.empty() && rel.begin() != rel.end() && std::next(rel.begin()) != rel.end())
    return root / *rel.begin();
  return root;
}

// How many leading folders two paths share.
size_t SharedFolders(const fs::path& a, const fs::path& b) {
  const fs::path pa = a.parent_path(), pb = b.parent_path();
  size_t n = 0;
  for (auto i = pa.begin(), j = pb.begin(); i != pa.end() && j != pb.end() && *i == *j; ++i, ++j)
    ++n;
  return n;
}

}  // namespace

std::vector<CollectionRobot> FindCollectionRobots(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw std::invalid_argument(dir + ": not a folder (robots check walks a folder of robots)");
  }
  const fs::path root = fs::path(dir).lexically_normal();
  std::vector<fs::path> urdfs, srdfs;
  fs::recursive_directory_iterator it(root,
                                      fs::directory_options::follow_directory_symlink |
                                          fs::directory_options::skip_permission_denied,
                                      ec);
  if (ec) throw std::invalid_argument(dir + ": cannot read folder (" + ec.message() + ")");
  for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    const fs::path& p = it->path();
    const std::string leaf = p.filename().string();
    if (it->is_directory(ec)) {
      if ((!leaf.empty() && leaf[0] == '.') || it.depth() >= 12) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    const std::string ext = LowerExt(p);
    if (ext == ".urdf") urdfs.push_back(p);
    if (ext == ".srdf") srdfs.push_back(p);
  }
  std::sort(urdfs.begin(), urdfs.end());
  std::sort(srdfs.begin(), srdfs.end());

  // URDFs by package, with their stems and robot names.
  struct UrdfInfo {
    fs::path path;
    std::string robot_name;
  };
  std::map<fs::path, std::vector<UrdfInfo>> by_package;
  for (const fs::path& u : urdfs) by_package[PackageOf(u, root)].push_back({u, XmlRobotName(u)});

  std::map<fs::path, std::vector<std::pair<fs::path, std::string>>> srdfs_of;  // urdf -> srdfs
  std::vector<CollectionRobot> out;
  for (const fs::path& s : srdfs) {
    const fs::path package = PackageOf(s, root);
    const std::vector<UrdfInfo>& candidates = by_package[package];
    // Same stem first, then same robot name; among several, the URDF whose path shares the most
    // folders with the SRDF's (robots/anymal_c/srdf/anymal.srdf goes with robots/anymal_c/urdf/
    // anymal.urdf, not robots/anymal_b/robots/anymal.urdf).
    const auto closest = [&](const auto& matches) -> const UrdfInfo* {
      const UrdfInfo* best = nullptr;
      size_t best_shared = 0;
      for (const UrdfInfo& u : candidates) {
        if (!matches(u)) continue;
        const size_t shared = SharedFolders(u.path, s);
        if (best == nullptr || shared > best_shared) {
          best = &u;
          best_shared = shared;
        }
      }
      return best;
    };
    std::string how = "stem";
    const UrdfInfo* match = closest([&](const UrdfInfo& u) { return u.path.stem() == s.stem(); });
    if (match == nullptr) {
      const std::string name = XmlRobotName(s);
      how = "robot name";
      match = closest([&](const UrdfInfo& u) { return !name.empty() && u.robot_name == name; });
    }
    if (match == nullptr) {
      out.push_back({"", s.string(), package.string(), ""});
      continue;
    }
    srdfs_of[match->path].push_back({s, how});
  }
  for (const fs::path& u : urdfs) {
    const std::string package = PackageOf(u, root).string();
    const auto found = srdfs_of.find(u);
    if (found == srdfs_of.end()) {
      out.push_back({u.string(), "", package, ""});
      continue;
    }
    for (const auto& [s, how] : found->second)
      out.push_back({u.string(), s.string(), package, how});
  }
  std::sort(out.begin(), out.end(), [](const CollectionRobot& a, const CollectionRobot& b) {
    const std::string& ka = a.urdf.empty() ? a.srdf : a.urdf;
    const std::string& kb = b.urdf.empty() ? b.srdf : b.urdf;
    return ka != kb ? ka < kb : a.srdf < b.srdf;
  });
  return out;
}

CollectionRow CheckCollectionRobot(const CollectionRobot& robot, const CollectionOptions& options) {
  CollectionRow row;
  row.robot = robot;
  if (robot.urdf.empty()) {
    row.status = CollectionStatus::kNoUrdf;
    row.reason = "no URDF of the same stem or robot name in its package";
    return row;
  }
  const auto t0 = std::chrono::steady_clock::now();
  try {
    RobotInputOptions input;
    input.package_paths = options.package_paths;
    input.srdf = robot.srdf;
    RobotScene scene = LoadRobotScene(robot.urdf, input);
    const Environment env = CollisionEnvironment(scene);
    CollisionOptions collision_options = scene.collision_options;
    collision_options.exact_meshes = collision_options.exact_meshes || options.exact_meshes;
    CollisionData coll(scene.robot, env, collision_options);
    KinematicsData kin(scene.robot);
    row.load_seconds = Seconds(t0);
    row.status = CollectionStatus::kLoaded;
    row.name = scene.robot.name;
    row.links = static_cast<int>(scene.robot.links.size());
    row.dofs = num_dofs(scene.robot);
    row.meshes = static_cast<int>(scene.robot.meshes.size());
    row.base = base::ToName(scene.robot.base_type);
    row.warnings = scene.warnings;
    if (!scene.srdf) return row;
    if (row.robot.srdf.empty()) {  // found by the loader (FindSrdf), as `check` finds it
      row.robot.srdf = scene.srdf->source;
      row.robot.paired_by = "found next to the URDF";
    }
    const Eigen::Isometry3d default_base = scene.robot.world_from_root;
    for (const SrdfPose& pose : scene.srdf->poses) {
      CollectionPose checked;
      checked.name = pose.name;
      checked.group = pose.group;
      const auto t1 = std::chrono::steady_clock::now();
      try {
        const Eigen::VectorXd q = ChooseQ(scene, "", pose.name, &checked.warnings);
        scene.robot.world_from_root = default_base;
        scene.robot.world_from_root = ChooseBase(scene, "", pose.name);
        ForwardKinematics(scene.robot, q, &kin);
        const CollisionReport report =
            CheckCollisions(scene.robot, kin, &coll, std::max(options.max_pairs, 1));
        checked.in_collision = report.in_collision;
        for (const ProximityPair& p : report.pairs)
          checked.pairs.push_back(PairName(scene.robot, env, p));
        for (const ProximityPair& p : report.hull_only)
          checked.hull_only.push_back(PairName(scene.robot, env, p));
      } catch (const std::exception& e) {
        checked.error = e.what();
      }
      checked.check_seconds = Seconds(t1);
      row.poses.push_back(std::move(checked));
    }
  } catch (const std::exception& e) {
    row.status = CollectionStatus::kRefused;
    row.reason = e.what();
    row.load_seconds = Seconds(t0);
  }
  return row;
}

}  // namespace planning
