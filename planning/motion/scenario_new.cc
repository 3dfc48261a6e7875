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
#include "planning/motion/robot_scene.h"
#include "planning/motion/success.h"
#include "planning/robot/ik.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace planning {
namespace {

namespace fs = std::filesystem;
using internal::Arm;
using internal::ChooseArm;
using internal::Origin;
using internal::Subtree;
using Json = nlohmann::ordered_json;

Json Vec(const Eigen::Vector3d& v) {
  const auto r = [](double x) { return std::round(x * 1e6) / 1e6; };  // µm: readable files
  return Json::array({r(v.x()), r(v.y()), r(v.z())});
}

Json QJson(const Eigen::VectorXd& q) {
  Json a = Json::array();
  for (Eigen::Index k = 0; k < q.size(); ++k) a.push_back(std::round(q[k] * 1e6) / 1e6);
  return a;
}

// Roll, pitch, yaw (URDF convention: R = Rz(yaw) Ry(pitch) Rx(roll)) of a rotation.
Json RpyJson(const Eigen::Matrix3d& r) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  double roll = std::atan2(r(2, 1), r(2, 2)), yaw = std::atan2(r(1, 0), r(0, 0));
  if (std::abs(std::cos(pitch)) < 1e-9) {  // gimbal lock: put it all in yaw
    roll = 0.0;
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  const auto q = [](double x) { return std::round(x * 1e9) / 1e9; };
  return Json::array({q(roll), q(pitch), q(yaw)});
}

}  // namespace

NewScenario MakeNewScenario(const std::string& urdf, const NewScenarioOptions& o) {
  if (o.task != "ring" && o.task != "reach") {
    throw std::invalid_argument("--task: '" + o.task + "' is not one of ring, reach");
  }
  RobotInputOptions input;
  input.package_paths = o.package_paths;
  input.srdf = o.srdf;
  const RobotScene scene = LoadRobotScene(urdf, input);
  const Robot& robot = scene.robot;
  NewScenario out;
  // The start: DefaultQ, moved into the limits (an SRDF reference pose may lie outside them,
  // and a plan must start inside).
  Eigen::VectorXd q0 = DefaultQ(scene, &out.notes);
  const Eigen::VectorXd lower = LowerLimits(robot), upper = UpperLimits(robot);
  const Eigen::VectorXd clamped = q0.cwiseMax(lower).cwiseMin(upper);
  const bool start_moved = clamped != q0;
  if (start_moved) {
    out.notes.push_back(
        "the default pose lies outside the joint limits: the start is that pose "
        "moved into them (written as start.q)");
    q0 = clamped;
  }
  const Arm arm = ChooseArm(scene, o.hand, &out.notes);
  out.hand_link = robot.links[arm.hand].name;
  KinematicsData kin(robot);
  ForwardKinematics(robot, q0, &kin);

  // Arm joints (the links they move) and the hand's approach axis and size.
  std::vector<int> arm_links;
  for (int p : arm.path) {
    const int j = robot.links[p].parent_joint;
    if (j >= 0 && robot.joints[j].dof >= 0) arm_links.push_back(p);
  }
  const Eigen::Vector3d hand_origin = Origin(kin, arm.hand);
  const Eigen::Vector3d last_joint = Origin(
      kin, arm_links.back() == arm.hand && arm_links.size() > 1 ? arm_links[arm_links.size() - 2]
                                                                : arm_links.back());
  Eigen::Vector3d tip_world = hand_origin;
  double hand_size = 0.0;
  const std::vector<int> below = Subtree(robot, arm.hand);
  if (!below.empty()) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int l : below) {
      centroid += Origin(kin, l);
      hand_size = std::max(hand_size, (Origin(kin, l) - hand_origin).norm());
    }
    tip_world = centroid / static_cast<double>(below.size());
  }
  Eigen::Vector3d approach = tip_world - hand_origin;
  if (approach.norm() < 1e-3) approach = hand_origin - last_joint;
  if (approach.norm() < 1e-6) approach = kin.world_from_link[arm.hand].linear().col(2);
  approach.normalize();
  hand_size = std::max(hand_size, 0.05);
  const Eigen::Matrix3d hand_rot = kin.world_from_link[arm.hand].linear();
  const Eigen::Vector3d axis_local = hand_rot.transpose() * approach;
  const Eigen::Vector3d tool_local = axis_local * hand_size;

  // Reach: the lengths between consecutive arm joints, plus the hand.
  const Eigen::Vector3d shoulder = Origin(kin, arm_links.front());
  double reach = hand_size;
  for (size_t i = 1; i < arm_links.size(); ++i)
    reach += (Origin(kin, arm_links[i]) - Origin(kin, arm_links[i - 1])).norm();
  reach += (hand_origin - Origin(kin, arm_links.back())).norm();

  // The hand chain: last three arm links, the hand, the tool point.
  std::vector<std::pair<int, Eigen::Vector3d>> chain;
  for (size_t i = arm_links.size() >= 3 ? arm_links.size() - 3 : 0; i < arm_links.size(); ++i) {
    if (arm_links[i] != arm.hand) chain.emplace_back(arm_links[i], Eigen::Vector3d::Zero());
  }
  chain.emplace_back(arm.hand, Eigen::Vector3d::Zero());
  chain.emplace_back(arm.hand, tool_local);
  const auto chain_points = [&](const KinematicsData& k) {
    Eigen::Matrix3Xd p(3, static_cast<Eigen::Index>(chain.size()));
    for (size_t i = 0; i < chain.size(); ++i)
      p.col(static_cast<Eigen::Index>(i)) = k.world_from_link[chain[i].first] * chain[i].second;
    return p;
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

  // Goal and start keep the arm's revolute joints 0.1 rad inside their limits (a planner's soft
  // limit terms need room); fingers and prismatic joints are not held to it.
  const auto AwayFromLimits = [&](const Eigen::VectorXd& q) {
    for (int k : arm.arm_dofs) {
      const Joint& joint = robot.joints[robot.dof_joints[k]];
      if (joint.type == JointType::kPrismatic) continue;
      const double room = std::min(0.1, 0.25 * (upper[k] - lower[k]));
      if (q[k] < lower[k] + room || q[k] > upper[k] - room) return false;
    }
    return true;
  };
  // Link pairs that touch in the start pose (no SRDF, or one that misses them) are disabled, as
  // MoveIt's set-up assistant disables pairs in collision by default; written to the file.
  CollisionOptions collision_options = scene.collision_options;
  std::vector<std::pair<std::string, std::string>> touching;
  {
    CollisionData self(robot, Environment{}, collision_options);
    const CollisionReport report = CheckCollisions(robot, kin, &self, 1000);
    for (const ProximityPair& p : report.pairs) {
      touching.emplace_back(robot.links[p.link_a].name, robot.links[p.link_b].name);
      collision_options.disabled_pairs.push_back(touching.back());
    }
    if (!touching.empty()) {
      out.notes.push_back(
          std::to_string(touching.size()) +
          " link pair(s) touch in the start pose: disabled (collision.disabled_pairs)");
    }
  }
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
      ring_rot = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d).toRotationMatrix();
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
  const std::vector<std::string> dof_names = DofNames(robot);
  Json j;
  j["name"] = o.name.empty() ? robot.name + "_" + o.task : o.name;
  j["description"] = "Made by `topoplan scenario new --task " + o.task + "` for robot '" +
                     robot.name + "': the hand '" + out.hand_link + "' reaches " +
                     (o.task == "ring" ? "through a ring" : "a target") +
                     " in front of the arm. Keys starting with // are comments.";
  j["robot"] = fs::absolute(urdf).lexically_normal().string();
  if (scene.srdf) j["srdf"] = fs::absolute(scene.srdf->source).lexically_normal().string();
  if (!o.package_paths.empty()) {
    Json pp = Json::array();
    for (const std::string& p : o.package_paths)
      pp.push_back(fs::absolute(p).lexically_normal().string());
    j["package_paths"] = pp;
  }
  if (!arm.other_dofs.empty()) {
    j["// frozen_joints"] = "joints below the hand (fingers), held at their start values";
    Json fj = Json::array();
    for (int k : arm.other_dofs) fj.push_back(dof_names[k]);
    j["frozen_joints"] = fj;
  }
  j["// robot_chains"] =
      "the hand chain: last arm links, the hand, the tool point (move the points"
      " to change what must pass through the ring)";
  Json points = Json::array();
  for (const auto& [link, xyz] : chain)
    points.push_back({{"link", robot.links[link].name}, {"xyz", Vec(xyz)}});
  j["robot_chains"] = Json::array({{{"name", "hand"}, {"points", points}}});
  if (!touching.empty()) {
    j["// collision"] =
        "link pairs in contact in the start pose, never checked (as MoveIt's "
        "set-up assistant disables them); remove a pair to check it";
    Json pairs = Json::array();
    for (const auto& [a, b] : touching) pairs.push_back(Json::array({a, b}));
    j["collision"] = {{"disabled_pairs", pairs}};
  }
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
  tasks.push_back(
      {{"name", "limits"},
       {"feature", {{"type", "joint_limits"}, {"margin", 0.05}, {"prismatic_margin", 0.002}}},
       {"precision", 1000}});
  tasks.push_back({{"name", "qdot"},
                   {"feature", {{"type", "joint_position"}}},
                   {"order", 1},
                   {"precision", 0.1},
                   {"final_precision", 0}});
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
  n.append(out.hand_link).append("', tool point ").append(base::FormatShortest(hand_size));
  n.append(" m ahead of it; reach ").append(base::FormatShortest(std::round(reach * 1000) / 1000));
  n.append(" m; goal by IK");
  out.notes.push_back(n);
  return out;
}

}  // namespace planning
