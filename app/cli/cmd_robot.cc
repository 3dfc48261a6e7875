// `topoplan fk` and `topoplan check`: forward kinematics and collision state of a URDF robot.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "app/cli/robot_flags.h"
#include "planning/motion/robot_scene.h"
#include "planning/collision/collision.h"
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
  std::string urdf, q, pose;
  planning::RobotInputOptions input;
  bool json = false;
};

struct CheckArgs {
  std::string input, q, pose;
  planning::RobotInputOptions robot_input;
  std::vector<std::string> objects;
  bool json = false, no_self = false;
  double margin = 0.0;
};

std::string PairName(const planning::RobotScene& s, const planning::Environment& env,
                     const planning::ProximityPair& p) {
  const std::string a = s.robot.links[p.link_a].name;
  if (p.object >= 0) return a + " vs object '" + env.objects[p.object].name + "'";
  return a + " vs " + s.robot.links[p.link_b].name;
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
                 "configuration v1,v2,... (rad / m) in the order of \"joints\" (default: zeros)");
  AddRobotInputFlags(fk, &fa->input, &fa->pose);
  fk->add_flag("--json", fa->json,
               "print {\"joints\": [...], \"links\": {name: {\"position\", \"rotation\"}}}");
  fk->footer(
      "q holds the independent movable joints (revolute, continuous, prismatic; mimic joints\n"
      "follow their master) in the order their <joint> elements appear in the URDF; \"joints\"\n"
      "lists them. Poses are in the world frame = the root link's frame; \"rotation\" is the 3x3\n"
      "matrix, row-major. A --q of the wrong length is an error (exit 2).");
  commands->push_back({fk, [fa]() {
                         const planning::RobotScene scene = planning::LoadRobotScene(fa->urdf, fa->input);
                         const planning::Robot& robot = scene.robot;
                         std::vector<std::string> warnings = scene.warnings;
                         const Eigen::VectorXd q =
                             planning::ChooseQ(scene, fa->q, fa->pose, &warnings);
                         ReportWarnings(warnings);
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
                           std::printf("robot %s: %d degrees of freedom, %zu links\n",
                                       robot.name.c_str(), planning::num_dofs(robot),
                                       robot.links.size());
                           std::printf("joints (q order):");
                           for (const std::string& n : planning::DofNames(robot))
                             std::printf(" %s", n.c_str());
                           std::printf("\n%-28s %10s %10s %10s\n", "link", "x", "y", "z");
                           for (size_t l = 0; l < robot.links.size(); ++l) {
                             const Eigen::Vector3d p = kin.world_from_link[l].translation();
                             std::printf("%-28s %10.5f %10.5f %10.5f\n",
                                         robot.links[l].name.c_str(), p.x(), p.y(), p.z());
                           }
                         }
                         return kExitOk;
                       }});

  // check ----------------------------------------------------------------------------------------
  auto ca = std::make_shared<CheckArgs>();
  CLI::App* check = root->add_subcommand(
      "check",
      "Collision state and minimum distance of a robot (and its scene) at a configuration");
  check
      ->add_option("INPUT", ca->input,
                   "robot URDF, or a scene JSON {\"robot\", \"q\", \"objects\"} (see README)")
      ->required();
  check->add_option("--q", ca->q, "configuration v1,v2,... in the `fk` joint order");
  check->add_option("--object", ca->objects,
                    "add an object: URDF[@x,y,z[,roll,pitch,yaw]] (repeatable; angles in rad)");
  AddRobotInputFlags(check, &ca->robot_input, &ca->pose);
  check->add_option("--margin", ca->margin,
                    "also list every link pair closer than this distance [m] (default 0)")
      ->check(FiniteIn(0.0, 10.0));
  check->add_flag("--no-self", ca->no_self, "skip self-collision (robot vs environment only)");
  check->add_flag("--json", ca->json,
                  "print {\"in_collision\", \"min_distance\", \"closest\", \"pairs\", ...}");
  check->footer(
      "Self-collision skips adjacent links (parent/child, fixed attachments). Exit code 0 when\n"
      "the configuration is collision-free, 1 when it collides, 2 on bad input.");
  commands->push_back(
      {check, [ca]() {
         planning::RobotScene scene = planning::LoadRobotScene(ca->input, ca->robot_input);
         for (const std::string& spec : ca->objects) planning::AddObjectSpec(spec, &scene);
         std::vector<std::string> warnings = scene.warnings;
         scene.q = planning::ChooseQ(scene, ca->q, ca->pose, &warnings);
         ReportWarnings(warnings);  // the pose asked about is checked, even outside the limits
         planning::CollisionOptions options = scene.collision_options;
         options.self_collision = options.self_collision && !ca->no_self;
         planning::KinematicsData kin(scene.robot);
         const planning::Environment env = planning::CollisionEnvironment(scene);
         planning::CollisionData coll(scene.robot, env, options);
         planning::ForwardKinematics(scene.robot, scene.q, &kin);
         planning::ProximityPair hit, closest;
         const bool colliding = planning::InCollision(scene.robot, kin, &coll, &hit);
         const double min_distance = planning::MinDistance(scene.robot, kin, &coll, &closest);
         std::vector<planning::ProximityPair> pairs;
         planning::ComputeProximity(scene.robot, kin, std::max(ca->margin, 0.0) + 1e-12, &coll,
                                    &pairs);
         if (ca->json) {
           Json out;
           out["robot"] = scene.robot.name;
           out["joints"] = planning::DofNames(scene.robot);
           out["q"] = std::vector<double>(scene.q.data(), scene.q.data() + scene.q.size());
           out["in_collision"] = colliding;
           out["min_distance"] = std::isfinite(min_distance) ? Json(min_distance) : Json(nullptr);
           out["closest"] =
               std::isfinite(min_distance) ? PairJson(scene, env, closest, true) : Json(nullptr);
           Json list = Json::array();
           for (const planning::ProximityPair& p : pairs)
             list.push_back(PairJson(scene, env, p, true));
           out["pairs"] = std::move(list);
           out["narrow_phase_calls"] = coll.narrow_phase_calls;
           std::cout << out.dump() << "\n";
         } else {
           std::printf("%s: %s\n", scene.robot.name.c_str(),
                       colliding ? ("IN COLLISION (" + PairName(scene, env, hit) + ")").c_str()
                                 : "collision-free");
           if (std::isfinite(min_distance)) {
             std::printf("minimum distance %.6f m (%s)\n", min_distance,
                         PairName(scene, env, closest).c_str());
           }
           for (const planning::ProximityPair& p : pairs) {
             std::printf("  %-50s %+.6f m\n", PairName(scene, env, p).c_str(), p.distance);
           }
           std::printf("narrow-phase calls: %lld\n",
                       static_cast<long long>(coll.narrow_phase_calls));
         }
         return colliding ? kExitFailed : kExitOk;
       }});
}

}  // namespace app
