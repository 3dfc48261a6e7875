// `topoplan fk` and `topoplan check`: forward kinematics and collision state of a URDF robot.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "app/cli/robot_flags.h"
#include "planning/collision/collision.h"
#include "planning/motion/robot_scene.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace app {
namespace {

using Json = nlohmann::ordered_json;

Json Vec(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json Rows(const Eigen::Matrix3d& r) {
  Json rows = Json::array();
  for (int i = 0; i < 3; ++i) rows.push_back(Json::array({r(i, 0), r(i, 1), r(i, 2)}));
  return rows;
}

struct FkArgs {
  std::string urdf, q, pose, base;
  planning::RobotInputOptions input;
  bool json = false;
};

struct CheckArgs {
  std::string input, q, pose, base;
  planning::RobotInputOptions robot_input;
  std::vector<std::string> objects;
  bool json = false, no_self = false, distance = false, exact_meshes = false;
  double margin = 0.0;
  int max_pairs = 100;
};

// x, y, z, qx, qy, qz, qw of a pose.
std::vector<double> PoseValues(const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond r(t.linear());
  const Eigen::Vector3d p = t.translation();
  return {p.x(), p.y(), p.z(), r.x(), r.y(), r.z(), r.w()};
}

std::string PoseText(const Eigen::Isometry3d& t) {
  std::string out;
  for (double v : PoseValues(t)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%.6g", out.empty() ? "" : ",", v);
    out.append(buf);
  }
  return out;
}

// Places the robot: --base, the free-base value of the pose (--pose, or the SRDF's first
// group_state when neither --q nor --pose chose the configuration, as DefaultQ), or the scene's.
void PlaceBase(planning::RobotScene* scene, const std::string& base, const std::string& pose,
               const std::string& q) {
  std::string named = pose;
  if (named.empty() && q.empty() && !scene->q_given && scene->srdf && !scene->srdf->poses.empty())
    named = scene->srdf->poses.front().name;
  scene->robot.world_from_root = planning::ChooseBase(*scene, base, named);
}

Json PairJson(const planning::RobotScene& s, const planning::Environment& env,
              const planning::ProximityPair& p, bool with_geometry) {
  Json j;
  j["link_a"] = s.robot.links[p.link_a].name;
  if (p.object >= 0) {
    j["object"] = env.objects[p.object].name;
  } else {
    j["link_b"] = s.robot.links[p.link_b].name;
  }
  if (with_geometry) {
    j["distance"] = p.distance;
    j["point_a"] = Vec(p.point_a);
    j["point_b"] = Vec(p.point_b);
    j["normal"] = Vec(p.normal);
  }
  return j;
}

}  // namespace

void AddRobotCommands(CLI::App* root, CommandList* commands) {
  // fk -------------------------------------------------------------------------------------------
  auto fa = std::make_shared<FkArgs>();
  CLI::App* fk =
      root->add_subcommand("fk", "Forward kinematics of a URDF robot: every link's pose");
  fk->add_option("ROBOT", fa->urdf, "robot URDF file")->required();
  fk->add_option("--q", fa->q,
                 "configuration v1,v2,... (rad / m) in the order of \"joints\" (default: zeros)")
      ->check(NonEmpty());
  AddRobotInputFlags(fk, &fa->input, &fa->pose);
  fk->add_option("--base", fa->base,
                 "pose of the root link x,y,z[,qx,qy,qz,qw] (default: the pose's free-base value, "
                 "the scene's \"base\", else identity)")
      ->check(NonEmpty());
  fk->add_flag("--json", fa->json,
               "print {\"joints\": [...], \"links\": {name: {\"position\", \"rotation\"}}}");
  fk->footer(
      "q holds the independent movable joints (revolute, continuous, prismatic; mimic joints\n"
      "follow their master) in the order their <joint> elements appear in the URDF; \"joints\"\n"
      "lists them. Poses are in the world frame (the root link's frame unless --base, a scene's\n"
      "\"base\" or a free base's pose value moves it); \"rotation\" is the 3x3\n"
      "matrix, row-major. A --q of the wrong length is an error (exit 2).");
  commands->push_back(
      {fk, [fa]() {
         planning::RobotScene scene = planning::LoadRobotScene(fa->urdf, fa->input);
         PlaceBase(&scene, fa->base, fa->pose, fa->q);
         const planning::Robot& robot = scene.robot;
         std::vector<std::string> warnings = scene.warnings;
         std::vector<std::string> notes = scene.notes;
         const Eigen::VectorXd q = planning::ChooseQ(scene, fa->q, fa->pose, &warnings, &notes);
         ReportWarnings(warnings);
         ReportNotes(notes);
         planning::KinematicsData kin(robot);
         planning::ForwardKinematics(robot, q, &kin);
         if (fa->json) {
           Json out;
           out["robot"] = robot.name;
           out["joints"] = planning::DofNames(robot);
           out["q"] = std::vector<double>(q.data(), q.data() + q.size());
           Json links = Json::object();
           for (size_t l = 0; l < robot.links.size(); ++l) {
             Json link;
             link["position"] = Vec(kin.world_from_link[l].translation());
             link["rotation"] = Rows(kin.world_from_link[l].linear());
             links[robot.links[l].name] = std::move(link);
           }
           out["links"] = std::move(links);
           std::cout << out.dump() << "\n";
         } else {
           std::printf("robot %s: %d degrees of freedom, %zu links\n", robot.name.c_str(),
                       planning::num_dofs(robot), robot.links.size());
           std::printf("joints (q order):");
           for (const std::string& n : planning::DofNames(robot)) std::printf(" %s", n.c_str());
           std::printf("\n%-28s %10s %10s %10s\n", "link", "x", "y", "z");
           for (size_t l = 0; l < robot.links.size(); ++l) {
             const Eigen::Vector3d p = kin.world_from_link[l].translation();
             std::printf("%-28s %10.5f %10.5f %10.5f\n", robot.links[l].name.c_str(), p.x(), p.y(),
                         p.z());
           }
         }
         return kExitOk;
       }});

  // check ----------------------------------------------------------------------------------------
  auto ca = std::make_shared<CheckArgs>();
  CLI::App* check = root->add_subcommand(
      "check", "Collision state of a robot (and its scene) at a configuration: yes/no per pair");
  check
      ->add_option("INPUT", ca->input,
                   "robot URDF, or a scene JSON {\"robot\", \"q\", \"objects\"} (see README)")
      ->required();
  check->add_option("--q", ca->q, "configuration v1,v2,... in the `fk` joint order")
      ->check(NonEmpty());
  check
      ->add_option("--object", ca->objects,
                   "add an object: URDF[@x,y,z[,roll,pitch,yaw]] (repeatable; angles in rad)")
      ->check(NonEmpty());
  AddRobotInputFlags(check, &ca->robot_input, &ca->pose);
  check
      ->add_option("--base", ca->base,
                   "pose of the root link x,y,z[,qx,qy,qz,qw] (default: the pose's free-base "
                   "value, the scene's \"base\", else identity)")
      ->check(NonEmpty());
  check->add_flag("--distance", ca->distance,
                  "also compute the minimum distance and the closest pair (distance queries on the "
                  "exact meshes)");
  check
      ->add_option("--margin", ca->margin,
                   "also list every link pair closer than this distance [m] (distance queries)")
      ->check(FiniteIn(0.0, 10.0));
  IntIn(check->add_option("--max-pairs", ca->max_pairs, "list at most this many colliding pairs"),
        1, 1000000);
  check->add_flag("--no-self", ca->no_self, "skip self-collision (robot vs environment only)");
  check->add_flag("--exact-meshes", ca->exact_meshes,
                  "collide link meshes as triangle BVHs only, without the convex-hull first test "
                  "(slower; the same verdict, as a cross-check)");
  check->add_flag("--json", ca->json,
                  "print {\"in_collision\", \"pairs\", \"hull_only\", \"base\", ...}");
  check->footer(
      "Self-collision skips adjacent links (parent/child, fixed attachments) and the SRDF's\n"
      "disabled pairs. Link meshes are tested as convex hulls first; a hull hit counts only when\n"
      "the exact triangles touch too (listed as hull-only otherwise). The verdict uses yes/no\n"
      "queries; distances are computed only with --distance or --margin. A pose outside the joint\n"
      "limits is checked with a warning (--strict: exit 2). Exit code 0 when the configuration is\n"
      "collision-free, 1 when it collides, 2 on bad input.");
  commands->push_back(
      {check, [ca]() {
         planning::RobotScene scene = planning::LoadRobotScene(ca->input, ca->robot_input);
         for (const std::string& spec : ca->objects) planning::AddObjectSpec(spec, &scene);
         std::vector<std::string> warnings = scene.warnings;
         std::vector<std::string> notes = scene.notes;
         scene.q = planning::ChooseQ(scene, ca->q, ca->pose, &warnings, &notes);
         PlaceBase(&scene, ca->base, ca->pose, ca->q);
         ReportWarnings(warnings);  // the pose asked about is checked, even outside the limits
         ReportNotes(notes);
         planning::CollisionOptions options = scene.collision_options;
         options.self_collision = options.self_collision && !ca->no_self;
         options.exact_meshes = options.exact_meshes || ca->exact_meshes;
         planning::KinematicsData kin(scene.robot);
         const planning::Environment env = planning::CollisionEnvironment(scene);
         planning::CollisionData coll(scene.robot, env, options);
         planning::ForwardKinematics(scene.robot, scene.q, &kin);
         const planning::CollisionReport report =
             planning::CheckCollisions(scene.robot, kin, &coll, ca->max_pairs);
         const bool want_distance = ca->distance || ca->margin > 0.0;
         planning::ProximityPair closest;
         double min_distance = std::numeric_limits<double>::infinity();
         std::vector<planning::ProximityPair> near;
         if (want_distance) {
           // Distances of the meshes themselves (the planners use the hulls' smooth distances).
           planning::CollisionOptions exact = options;
           exact.exact_meshes = true;
           planning::CollisionData dist(scene.robot, env, exact);
           min_distance = planning::MinDistance(scene.robot, kin, &dist, &closest);
           if (ca->margin > 0.0)
             planning::ComputeProximity(scene.robot, kin, ca->margin, &dist, &near);
           coll.narrow_phase_calls += dist.narrow_phase_calls;
         }
         const bool free_base = scene.robot.base_type != planning::BaseType::kFixed;
         if (ca->json) {
           Json out;
           out["robot"] = scene.robot.name;
           out["joints"] = planning::DofNames(scene.robot);
           out["q"] = std::vector<double>(scene.q.data(), scene.q.data() + scene.q.size());
           out["base_type"] = base::ToName(scene.robot.base_type);
           out["base"] = PoseValues(scene.robot.world_from_root);
           out["in_collision"] = report.in_collision;
           Json list = Json::array();
           for (const planning::ProximityPair& p : report.pairs)
             list.push_back(PairJson(scene, env, p, false));
           out["pairs"] = std::move(list);
           Json hull = Json::array();
           for (const planning::ProximityPair& p : report.hull_only)
             hull.push_back(PairJson(scene, env, p, false));
           out["hull_only"] = std::move(hull);
           if (want_distance) {
             const bool finite = std::isfinite(min_distance);
             out["min_distance"] = finite ? Json(min_distance) : Json(nullptr);
             out["closest"] = finite ? PairJson(scene, env, closest, true) : Json(nullptr);
           }
           if (ca->margin > 0.0) {
             Json nl = Json::array();
             for (const planning::ProximityPair& p : near)
               nl.push_back(PairJson(scene, env, p, true));
             out["near"] = std::move(nl);
           }
           out["narrow_phase_calls"] = coll.narrow_phase_calls;
           std::cout << out.dump() << "\n";
         } else {
           std::string verdict = "collision-free";
           if (report.in_collision) {
             verdict = "IN COLLISION (";
             verdict.append(planning::PairName(scene.robot, env, report.pairs.front())).append(")");
             if (report.pairs.size() > 1) {
               verdict.append(", ").append(std::to_string(report.pairs.size()));
               verdict.append(" colliding pairs");
             }
           }
           std::printf("%s: %s\n", scene.robot.name.c_str(), verdict.c_str());
           if (free_base || !ca->base.empty()) {
             std::printf("base (%s%s%s): %s\n", base::ToName(scene.robot.base_type),
                         scene.robot.base_joint.empty() ? "" : ", joint ",
                         scene.robot.base_joint.c_str(),
                         PoseText(scene.robot.world_from_root).c_str());
           }
           if (report.pairs.size() > 1) {
             for (const planning::ProximityPair& p : report.pairs)
               std::printf("  colliding: %s\n", planning::PairName(scene.robot, env, p).c_str());
           }
           for (const planning::ProximityPair& p : report.hull_only) {
             std::printf("  hull-only (convex hulls overlap, meshes do not): %s\n",
                         planning::PairName(scene.robot, env, p).c_str());
           }
           if (want_distance && std::isfinite(min_distance)) {
             std::printf("minimum distance %.6f m (%s)\n", min_distance,
                         planning::PairName(scene.robot, env, closest).c_str());
           }
           for (const planning::ProximityPair& p : near) {
             std::printf("  %-50s %+.6f m\n", planning::PairName(scene.robot, env, p).c_str(),
                         p.distance);
           }
           std::printf("narrow-phase calls: %lld\n",
                       static_cast<long long>(coll.narrow_phase_calls));
         }
         return report.in_collision ? kExitFailed : kExitOk;
       }});
}

}  // namespace app
