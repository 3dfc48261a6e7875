// MakeNewScenario (planning/motion/scenario_new.h): hand, chain, ring, goal by IK, box.
#include "planning/motion/scenario_new.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "base/assets.h"
#include "base/numbers.h"
#include "planning/collision/collision.h"
#include "planning/motion/internal/scenario_arm.h"
#include "planning/motion/internal/scenario_file.h"
#include "planning/motion/internal/scenario_unwrap.h"
#include "planning/motion/robot_scene.h"
#include "planning/motion/success.h"
#include "planning/robot/ik.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/pose.h"
#include "planning/robot/robot_io.h"

namespace planning {
namespace {

namespace fs = std::filesystem;
using internal::ArmSetup;
using internal::Json;
using internal::QJson;
using internal::RpyJson;
using internal::Vec;

}  // namespace

NewScenario MakeNewScenario(const std::string& urdf, const NewScenarioOptions& o) {
  if (o.task != "ring" && o.task != "reach" && o.task != "unwrap") {
    throw std::invalid_argument("--task: '" + o.task + "' is not one of ring, reach, unwrap");
  }
  RobotInputOptions input;
  input.package_paths = o.package_paths;
  input.srdf = o.srdf;
  const RobotScene scene = LoadRobotScene(urdf, input);
  NewScenario out;
  const ArmSetup setup = internal::SetUpArm(scene, o.hand, &out.notes);
  if (o.task == "unwrap")
    return internal::MakeUnwrapScenario(scene, urdf, o, setup, std::move(out));
  const Robot& robot = scene.robot;
  const Eigen::VectorXd& q0 = setup.q0;
  const bool start_moved = setup.start_moved;
  const internal::Arm& arm = setup.arm;
  out.hand_link = robot.links[arm.hand].name;
  KinematicsData kin(robot);
  ForwardKinematics(robot, q0, &kin);
  const std::vector<int>& arm_links = setup.arm_links;
  const Eigen::Vector3d& approach = setup.approach;
  const Eigen::Vector3d& tool_local = setup.tool_local;
  const Eigen::Vector3d& shoulder = setup.shoulder;
  const double hand_size = setup.hand_size, reach = setup.reach;
  const Eigen::Vector3d axis_local = tool_local / hand_size;  // the approach axis, hand frame

  // The hand chain: last three arm links, the hand, the tool point.
  internal::LinkPoints chain;
  for (size_t i = arm_links.size() >= 3 ? arm_links.size() - 3 : 0; i < arm_links.size(); ++i) {
    if (arm_links[i] != arm.hand) chain.emplace_back(arm_links[i], Eigen::Vector3d::Zero());
  }
  chain.emplace_back(arm.hand, Eigen::Vector3d::Zero());
  chain.emplace_back(arm.hand, tool_local);
  const auto chain_points = [&](const KinematicsData& k) {
    return internal::WorldPoints(chain, k);
  };

  // The object: a ring (its chain "loop"), axis along +x.
  const std::string object_path =
      o.object.empty() ? base::AssetPath("objects/ring.urdf") : o.object;
  const Robot ring = LoadRobot(object_path);
  double ring_radius = 0.0;
  int loop = -1;
  if (o.task == "ring") {
    loop = FindChain(ring, "loop");
    KinematicsData rk(ring);
    ForwardKinematics(ring, Eigen::VectorXd::Zero(num_dofs(ring)), &rk);
    Eigen::Matrix3Xd lp;
    ChainPoints(ring, rk, loop, &lp);
    for (Eigen::Index k = 0; k < lp.cols(); ++k)
      ring_radius = std::max(ring_radius, lp.col(k).norm());
  }

  const auto AwayFromLimits = [&](const Eigen::VectorXd& q) {
    return internal::AwayFromLimits(robot, setup, q);
  };
  const CollisionOptions& collision_options = setup.collision_options;
  IkData ik_data(robot);
  IkOptions ik_options;
  ik_options.starts = 24;
  ik_options.random_seed = o.seed;
  // Candidate placements (ring centre, its axis = the approach direction): first straight ahead
  // of the hand in the start pose (the hand moves on along its approach axis, through the ring),
  // then in front of the first arm joint along the base's +x at 35–65 % of the reach.
  struct Placement {
    Eigen::Vector3d center, axis;
    std::string what;
  };
  std::vector<Placement> placements;
  const Eigen::Vector3d tool_start = kin.world_from_link[arm.hand] * tool_local;
  for (double ahead : {0.5, 0.8}) {
    placements.push_back({tool_start + approach * (ahead * ring_radius + 0.05), approach,
                          "ahead of the hand by " + base::FormatShortest(ahead) + " ring radii"});
  }
  for (double fraction : {0.5, 0.6, 0.4}) {
    for (double height : {0.25, 0.4, 0.1}) {
      placements.push_back({shoulder + Eigen::Vector3d::UnitX() * (fraction * reach) +
                                Eigen::Vector3d::UnitZ() * (height * reach),
                            Eigen::Vector3d::UnitX(),
                            "+x " + base::FormatShortest(fraction) + " of the reach, height " +
                                base::FormatShortest(height)});
    }
  }
  std::string tried;
  bool found = false;
  NewScenario fallback;  // the chosen placement's goal, target, centre, start and notes
  Eigen::Vector3d fallback_axis = Eigen::Vector3d::UnitX();
  Eigen::Matrix3d fallback_rot = Eigen::Matrix3d::Identity();
  Eigen::Vector3d d = Eigen::Vector3d::UnitX();
  Eigen::Matrix3d ring_rot = Eigen::Matrix3d::Identity();
  for (const Placement& placement : placements) {
    {
      const Eigen::Vector3d center = placement.center;
      d = placement.axis.normalized();
      ring_rot = RotationFromZ(d);
      const Eigen::Vector3d target = center + d * (o.task == "ring" ? 0.6 * hand_size : 0.0);
      Environment env;
      if (o.task == "ring") {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = center;
        pose.linear() = ring_rot;
        AddObject(ring, pose, "ring", &env);
      }
      CollisionData coll(robot, env, collision_options);
      KinematicsData k(robot);
      ForwardKinematics(robot, q0, &k);
      tried.append(tried.empty() ? "" : "; ").append(placement.what);
      if (InCollision(robot, k, &coll)) {
        tried.append(": the start touches the ring or itself");
        continue;
      }
      const Eigen::Matrix3Xd loop_points =
          o.task == "ring" ? ObjectChainPoints(env, 0, loop) : Eigen::Matrix3Xd();
      IkProblem problem;
      IkTarget t;
      t.link = arm.hand;
      t.offset = tool_local;
      t.position = target;
      t.axis = IkAxis{axis_local, d};
      problem.targets.push_back(t);
      problem.seed = q0;
      problem.frozen_dofs = arm.other_dofs;
      ik_options.is_valid = [&](const Eigen::VectorXd& q) {
        if (!AwayFromLimits(q)) return false;
        ForwardKinematics(robot, q, &k);
        if (InCollision(robot, k, &coll)) return false;
        return o.task != "ring" || ChainThroughLoop(chain_points(k), loop_points);
      };
      const IkResult r = SolveIk(robot, problem, ik_options, &ik_data);
      if (r.status != IkStatus::kSolved) {
        tried.append(": IK ").append(IkStatusName(r.status));
        continue;
      }
      NewScenario cand;
      cand.goal_q = r.q;
      cand.tool_target = target;
      cand.ring_center = center;
      cand.notes.push_back("ring placed " + placement.what);
      // The start: the hand in front of the ring on its axis (tool 0.1 m + its length before the
      // ring's plane, same approach), reached from the goal by IK; a planner then moves the hand
      // on along its axis through the ring. Kept only if collision-free and not yet through.
      for (double standoff : {0.6 * hand_size + 0.1, 0.3 * hand_size + 0.05, 0.05}) {
        if (o.task != "ring") break;
        IkProblem before = problem;
        before.targets[0].position = center - d * standoff;
        before.seed = r.q;
        ik_options.is_valid = [&](const Eigen::VectorXd& q) {
          if (!AwayFromLimits(q)) return false;
          ForwardKinematics(robot, q, &k);
          return !InCollision(robot, k, &coll) && !ChainThroughLoop(chain_points(k), loop_points);
        };
        const IkResult pre = SolveIk(robot, before, ik_options, &ik_data);
        if (pre.status != IkStatus::kSolved) continue;
        cand.start_q = pre.q;
        cand.notes.push_back("start: the tool " +
                             base::FormatShortest(std::round(standoff * 1e3) / 1e3) +
                             " m in front of the ring (inverse kinematics)");
        break;
      }
      // A placement with a goal but no start in front of the ring is kept as a fallback; the
      // search goes on for one with both (a plan from the default pose must first go around).
      if (cand.start_q.size() == 0 && o.task == "ring") {
        tried.append(": goal found, no start in front of the ring");
        if (!found) {
          fallback = std::move(cand);
          fallback_axis = d;
          fallback_rot = ring_rot;
        }
        found = true;
        continue;
      }
      fallback = std::move(cand);
      fallback_axis = d;
      fallback_rot = ring_rot;
      found = true;
      break;
    }
  }
  if (found) {
    out.goal_q = fallback.goal_q;
    out.tool_target = fallback.tool_target;
    out.ring_center = fallback.ring_center;
    out.start_q = fallback.start_q;
    out.notes.insert(out.notes.end(), fallback.notes.begin(), fallback.notes.end());
    if (o.task == "ring" && out.start_q.size() == 0) {
      out.notes.push_back("no start in front of the ring found (tried " + tried +
                          "); the start is the default pose");
    }
    d = fallback_axis;  // the ring's axis and orientation of the chosen placement
    ring_rot = fallback_rot;
  }
  if (!found) {
    throw std::invalid_argument(urdf + ": no placement of the " + o.task + " works for hand '" +
                                out.hand_link + "' (tried " + tried + ")");
  }

  // The file.
  Json j = internal::ScenarioHead(
      scene, urdf, o, setup,
      "Made by `topoplan scenario new --task " + o.task + "` for robot '" + robot.name +
          "': the hand '" + out.hand_link + "' reaches " +
          (o.task == "ring" ? "through a ring" : "a target") +
          " in front of the arm. Keys starting with // are comments.",
      "hand", chain,
      "the hand chain: last arm links, the hand, the tool point (move the points"
      " to change what must pass through the ring)");
  if (o.task == "ring") {
    j["// objects"] =
        "the ring: move it with xyz (its axis along x by rpy); the goal below follows"
        " from final_pose";
    j["objects"] = Json::array({{{"name", "ring"},
                                 {"urdf", fs::absolute(object_path).lexically_normal().string()},
                                 {"xyz", Vec(out.ring_center)},
                                 {"rpy", RpyJson(ring_rot)},
                                 {"capsules", {{"chain", "loop"}, {"radius", 0.012}}}}});
    j["writhe_report"] = {{"chain", "hand"}, {"object", "ring"}, {"object_chain", "loop"}};
  }
  if (out.start_q.size() > 0) {
    j["// start"] =
        "the hand in front of the ring, found by inverse kinematics; or {\"pose\": "
        "NAME} for an SRDF group_state";
    j["start"] = {{"q", QJson(out.start_q)}};
  } else if (scene.srdf && !scene.srdf->poses.empty() && !start_moved) {
    j["start"] = {{"pose", scene.srdf->poses.front().name}};
  } else {
    j["start"] = {{"q", QJson(q0)}};
  }
  j["problem"] = {
      {"T", 32}, {"duration", 4.0}, {"dynamic", true}, {"h_rate", 1.0}, {"w_rate", 1.0}};
  const Json box_center = Vec(out.tool_target);
  const double half = std::max(0.05, 0.5 * hand_size);
  Json tasks = Json::array();
  if (o.task == "ring") {
    tasks.push_back({{"name", "writhe"},
                     {"feature",
                      {{"type", "writhe"},
                       {"chain", "hand"},
                       {"object", "ring"},
                       {"object_chain", "loop"},
                       {"output", "matrix"}}},
                     {"target", {{"type", "final_pose"}}},
                     {"precision", 100},
                     {"final_precision", 1000}});
  }
  tasks.push_back({{"name", "box"},
                   {"feature",
                    {{"type", "box"},
                     {"link", out.hand_link},
                     {"offset", Vec(tool_local)},
                     {"center", box_center},
                     {"half_extent", Vec(Eigen::Vector3d::Constant(half))},
                     {"margin", 0.01}}},
                   {"precision", 0},
                   {"final_precision", 1000}});
  tasks.push_back(
      {{"name", "reach"},
       {"feature", {{"type", "position"}, {"link", out.hand_link}, {"offset", Vec(tool_local)}}},
       {"target", {{"type", "interpolate"}, {"value", box_center}}},
       {"precision", 10},
       {"final_precision", 100}});
  tasks.push_back({{"name", "collision"},
                   {"feature", {{"type", "collision"}, {"margin", 0.02}}},
                   {"precision", 100}});
  tasks.push_back(internal::LimitsTask(0.05, 1000));
  tasks.push_back(internal::QdotTask());
  j["tasks"] = tasks;
  j["// final_pose"] =
      "init: the goal found by inverse kinematics (topoplan ik), all joints in fk"
      " order";
  j["final_pose"] = {{"tasks", Json::array({"reach", "box", "collision", "limits"})},
                     {"init", QJson(out.goal_q)},
                     {"alpha", 0.05}};
  Json success = {{"inside_box", "box"}};
  if (o.task == "ring") success["through_loop"] = true;
  j["success"] = success;
  j["aico"] = {{"max_iterations", 40},      {"tolerance", 0.01}, {"damping", 1.0},
               {"sweep_mode", "forwardly"}, {"max_step", 0.3},   {"rollout_init", true},
               {"rollout_prior", 100}};
  j["rrt"] = {{"range", 0.5}, {"resolution", 0.02}, {"goal_bias", 0.1}, {"max_checks", 100000}};
  j["check_resolution"] = 0.02;
  out.json = std::move(j);
  std::string n = "hand '";
  n.append(out.hand_link)
      .append("', tool point ")
      .append(base::FormatShortest(std::round(hand_size * 1000) / 1000));
  n.append(" m ahead of it; reach ").append(base::FormatShortest(std::round(reach * 1000) / 1000));
  n.append(" m; goal by IK");
  out.notes.push_back(n);
  return out;
}

}  // namespace planning
