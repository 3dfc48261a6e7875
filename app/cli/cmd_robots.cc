// `topoplan robots check DIR`: every robot of a folder loaded and checked in its SRDF poses.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "planning/motion/robot_collection.h"

namespace app {
namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

struct RobotsArgs {
  std::string dir;
  std::vector<std::string> package_paths;
  int max_pairs = 20;
  bool json = false, no_times = false, exact_meshes = false;
};

// `path` relative to `root` when it lies below it.
std::string Shown(const std::string& path, const std::string& root) {
  if (path.empty()) return "-";
  const fs::path rel = fs::path(path).lexically_relative(fs::path(root).lexically_normal());
  return rel.empty() || *rel.begin() == ".." ? path : rel.string();
}

const char* Verdict(const planning::CollectionPose& p) {
  if (!p.error.empty()) return "error";
  return p.in_collision ? "collision" : "free";
}

// The first line of a loader message, without the file name prefix the row already shows.
std::string ShortReason(std::string reason, const std::string& file) {
  const size_t nl = reason.find('\n');
  if (nl != std::string::npos) reason.resize(nl);
  if (!file.empty() && reason.compare(0, file.size(), file) == 0) {
    reason.erase(0, file.size());
    while (!reason.empty() && (reason[0] == ':' || reason[0] == ' ')) reason.erase(0, 1);
  }
  return reason;
}

Json RowJson(const planning::CollectionRow& r, const std::string& root, bool times) {
  Json j;
  j["urdf"] = r.robot.urdf.empty() ? Json(nullptr) : Json(Shown(r.robot.urdf, root));
  j["srdf"] = r.robot.srdf.empty() ? Json(nullptr) : Json(Shown(r.robot.srdf, root));
  j["paired_by"] = r.robot.paired_by.empty() ? Json(nullptr) : Json(r.robot.paired_by);
  j["status"] = base::ToName(r.status);
  if (r.status != planning::CollectionStatus::kLoaded) j["reason"] = r.reason;
  if (r.status == planning::CollectionStatus::kLoaded) {
    j["name"] = r.name;
    j["links"] = r.links;
    j["dofs"] = r.dofs;
    j["meshes"] = r.meshes;
    j["base"] = r.base;
  }
  j["warnings"] = r.warnings;
  if (times) j["load_s"] = r.load_seconds;
  Json poses = Json::array();
  for (const planning::CollectionPose& p : r.poses) {
    Json pj;
    pj["name"] = p.name;
    pj["group"] = p.group;
    pj["verdict"] = Verdict(p);
    pj["pairs"] = p.pairs;
    pj["hull_only"] = p.hull_only;
    pj["warnings"] = p.warnings;
    if (!p.error.empty()) pj["error"] = p.error;
    if (times) pj["check_s"] = p.check_seconds;
    poses.push_back(std::move(pj));
  }
  j["poses"] = std::move(poses);
  return j;
}

void PrintRow(const planning::CollectionRow& r, const std::string& root, bool times) {
  const std::string file = r.robot.urdf.empty() ? r.robot.srdf : r.robot.urdf;
  std::printf("%-60s %-8s", Shown(file, root).c_str(), base::ToName(r.status));
  if (r.status != planning::CollectionStatus::kLoaded) {
    std::printf(" %s\n", ShortReason(r.reason, file).c_str());
    return;
  }
  std::printf(" %5d %4d %6d %-8s %-28s", r.links, r.dofs, r.meshes, r.base.c_str(),
              r.robot.srdf.empty() ? "-" : fs::path(r.robot.srdf).filename().string().c_str());
  if (times) std::printf(" %7.3f", r.load_seconds);
  std::printf("\n");
  for (const std::string& w : r.warnings) std::printf("    warning: %s\n", w.c_str());
  for (const planning::CollectionPose& p : r.poses) {
    std::printf("    pose %-24s %-9s", p.name.c_str(), Verdict(p));
    if (times) std::printf(" %8.3f ms", 1e3 * p.check_seconds);
    if (!p.hull_only.empty()) std::printf("  hull-only %zu", p.hull_only.size());
    if (!p.pairs.empty()) {
      std::printf("  %s", p.pairs.front().c_str());
      if (p.pairs.size() > 1) std::printf(" (+%zu)", p.pairs.size() - 1);
    }
    if (!p.error.empty()) std::printf("  %s", p.error.c_str());
    std::printf("\n");
    for (const std::string& w : p.warnings) std::printf("      warning: %s\n", w.c_str());
  }
}

int Run(const RobotsArgs& a) {
  const std::vector<planning::CollectionRobot> robots = planning::FindCollectionRobots(a.dir);
  planning::CollectionOptions options;
  options.package_paths = a.package_paths;
  options.package_paths.push_back(a.dir);  // the folder itself may be (or hold) the packages
  options.max_pairs = a.max_pairs;
  options.exact_meshes = a.exact_meshes;
  std::vector<planning::CollectionRow> rows;
  const StopCheck stop(0.0);  // Ctrl-C stops between robots
  for (size_t i = 0; i < robots.size(); ++i) {
    stop.Poll();
    const std::string& file = robots[i].urdf.empty() ? robots[i].srdf : robots[i].urdf;
    Progress("robots check: [%zu/%zu] %s", i + 1, robots.size(), Shown(file, a.dir).c_str());
    rows.push_back(planning::CheckCollectionRobot(robots[i], options));
  }
  EndProgress();
  int loaded = 0, refused = 0, no_urdf = 0, poses = 0, free = 0, colliding = 0, errors = 0,
      hull_only = 0;
  for (const planning::CollectionRow& r : rows) {
    loaded += r.status == planning::CollectionStatus::kLoaded;
    refused += r.status == planning::CollectionStatus::kRefused;
    no_urdf += r.status == planning::CollectionStatus::kNoUrdf;
    for (const planning::CollectionPose& p : r.poses) {
      ++poses;
      free += p.error.empty() && !p.in_collision;
      colliding += p.error.empty() && p.in_collision;
      errors += !p.error.empty();
      hull_only += !p.hull_only.empty();
    }
  }
  const bool times = !a.no_times;
  if (a.json) {
    Json out;
    out["dir"] = a.dir;
    Json list = Json::array();
    for (const planning::CollectionRow& r : rows) list.push_back(RowJson(r, a.dir, times));
    out["robots"] = std::move(list);
    out["summary"] = {{"rows", rows.size()},
                      {"loaded", loaded},
                      {"refused", refused},
                      {"srdf_without_urdf", no_urdf},
                      {"poses", poses},
                      {"free", free},
                      {"in_collision", colliding},
                      {"pose_errors", errors},
                      {"poses_with_hull_only_hits", hull_only}};
    std::cout << out.dump() << "\n";
  } else {
    std::printf("%-60s %-8s %5s %4s %6s %-8s %-28s%s\n", "URDF (or SRDF)", "status", "links",
                "dofs", "meshes", "base", "SRDF", times ? "  load s" : "");
    for (const planning::CollectionRow& r : rows) PrintRow(r, a.dir, times);
    std::printf(
        "\n%zu rows: %d loaded, %d refused, %d SRDF without URDF; %d SRDF poses: %d free, %d in "
        "collision, %d not applied; %d with hull-only hits (not collisions)\n",
        rows.size(), loaded, refused, no_urdf, poses, free, colliding, errors, hull_only);
  }
  return refused == 0 && no_urdf == 0 && colliding == 0 && errors == 0 ? kExitOk : kExitFailed;
}

}  // namespace

void AddRobotsCommand(CLI::App* root, CommandList* commands) {
  CLI::App* robots =
      root->add_subcommand("robots", "Survey a folder of robots (a ROS workspace, a collection)");
  robots->require_subcommand(1);
  auto a = std::make_shared<RobotsArgs>();
  CLI::App* check = robots->add_subcommand(
      "check", "Load every URDF below DIR, pair it with its SRDF, check each SRDF pose");
  check->add_option("DIR", a->dir, "folder to walk (symbolic links followed)")->required();
  check
      ->add_option("--package-path", a->package_paths,
                   "extra root for package:// URIs (repeatable); DIR itself is always searched")
      ->check(NonEmpty());
  IntIn(check->add_option("--max-pairs", a->max_pairs,
                          "colliding pairs listed per pose (default 20)"),
        1, 100000);
  check->add_flag("--exact-meshes", a->exact_meshes,
                  "collide link meshes as triangle BVHs only (no convex-hull first test; slower)");
  check->add_flag("--json", a->json, "print {\"robots\": [...], \"summary\": {...}}");
  check->add_flag("--no-times", a->no_times,
                  "leave out load and check times (output identical run to run)");
  check->footer(
      "One row per URDF (and per SRDF paired with it): loaded, or refused with the loader's\n"
      "reason; links, degrees of freedom, meshes, base (fixed / floating / planar), the SRDF and\n"
      "how it was paired (same file stem, else same <robot name> in the same package), load time.\n"
      "Under each row, every SRDF group_state checked as `check --pose NAME` would: free or in\n"
      "collision (first pair, number of others), hull-only hits (convex hulls overlap, meshes do\n"
      "not: not collisions), check time. Exit 0 when every robot loaded and every pose is\n"
      "collision-free, 1 otherwise, 2 when DIR is not a folder.");
  commands->push_back({check, [a]() { return Run(*a); }});
}

}  // namespace app
