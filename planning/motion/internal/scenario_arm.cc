// The arm of `scenario new` (internal/scenario_arm.h).
#include "planning/motion/internal/scenario_arm.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <stdexcept>

#include "base/str_cat.h"

namespace planning::internal {
namespace {
// A subtree reaching this far (m) from where the tree branches is an arm, not a finger (FindArm).
constexpr double kArmReach = 0.2;
// ... and at least this fraction of the path from the root to the branch (a hand's fingers are
// short against the arm that carries them: the SDH's reach 0.2 m at the end of a 1.2 m arm).
constexpr double kFingerFraction = 0.25;

// The arm ending at link `hand` (its path from the root).
Arm ArmTo(const Robot& robot, int hand) {
  Arm arm;
  for (int l = hand; l > 0; l = robot.joints[robot.links[l].parent_joint].parent_link) {
    arm.path.push_back(l);
  }
  arm.path.push_back(0);
  std::reverse(arm.path.begin(), arm.path.end());
  arm.hand = hand;
  return arm;
}

// Fills arm_dofs / other_dofs from arm->path; throws when fewer than 2 joints of it move.
void SplitDofs(const Robot& robot, const std::string& where, Arm* arm) {
  std::vector<bool> on_arm(robot.dof_joints.size(), false);
  for (int p : arm->path) {
    const int j = robot.links[p].parent_joint;
    if (j >= 0 && robot.joints[j].dof >= 0) on_arm[robot.joints[j].dof] = true;
  }
  for (size_t k = 0; k < on_arm.size(); ++k) {
    (on_arm[k] ? arm->arm_dofs : arm->other_dofs).push_back(static_cast<int>(k));
  }
  if (arm->arm_dofs.size() < 2) {
    throw std::invalid_argument(robot.source + ": no arm found (" + where + " after " +
                                std::to_string(arm->arm_dofs.size()) +
                                " movable joint(s); scenario new needs a serial arm of 2 or more;"
                                " name the hand link with --hand)");
  }
}

Arm FindArm(const Robot& robot) {
  const int nl = static_cast<int>(robot.links.size());
  std::vector<std::vector<int>> children(nl);
  for (const Joint& j : robot.joints) children[j.parent_link].push_back(j.child_link);
  // Movable joints in each subtree (children come after parents: links are in topological order).
  std::vector<int> movable(nl, 0);
  for (int l = nl - 1; l >= 0; --l) {
    for (int c : children[l]) {
      movable[l] += movable[c] + (robot.joints[robot.links[c].parent_joint].dof >= 0 ? 1 : 0);
    }
  }
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd::Zero(num_dofs(robot)), &kin);
  Arm arm;
  int l = 0;
  arm.path.push_back(0);
  double walked = 0.0;  // Σ distances between the link origins of the path so far, m
  for (;;) {
    std::vector<int> moving;
    for (int c : children[l]) {
      if (movable[c] > 0 || robot.joints[robot.links[c].parent_joint].dof >= 0) moving.push_back(c);
    }
    if (moving.empty()) break;
    if (moving.size() > 1) {
      // A branch: fingers (subtrees reaching less than max(kArmReach, kFingerFraction × the
      // path walked so far) from this link in the zero pose) make this link the hand; else the
      // walk follows the long subtree with the most movable joints (a humanoid's torso rather
      // than a leg, then one of its arms).
      const double arm_reach = std::max(kArmReach, kFingerFraction * walked);
      int best = -1, best_count = -1;
      for (int c : moving) {
        double r = 0.0;
        for (int d = c; d < nl; ++d) {  // d in c's subtree: walk up until at or above c
          int a = d;
          while (a > c) a = robot.joints[robot.links[a].parent_joint].parent_link;
          if (a == c) r = std::max(r, (Origin(kin, d) - Origin(kin, l)).norm());
        }
        const int count = movable[c] + (robot.joints[robot.links[c].parent_joint].dof >= 0 ? 1 : 0);
        if (r >= arm_reach && count > best_count) best = c, best_count = count;
      }
      if (best < 0) break;
      arm.branch_choices.push_back(robot.links[l].name + " → " + robot.links[best].name);
      moving = {best};
    }
    walked += (Origin(kin, moving[0]) - Origin(kin, l)).norm();
    l = moving[0];
    arm.path.push_back(l);
  }
  arm.hand = l;
  SplitDofs(robot,
            "walking down from '" + robot.links[0].name + "', the tree branches at '" +
                robot.links[l].name + "'",
            &arm);
  return arm;
}

}  // namespace

// The arm: to `hand` when given; else FindArm; when the tree branches before a serial arm (a
// humanoid, a mobile manipulator), to the parent link of the first SRDF end effector that is not a
// foot or leg (by its name or group) and has an arm of 2 or more joints.
Arm ChooseArm(const RobotScene& scene, const std::string& hand, std::vector<std::string>* notes) {
  const Robot& robot = scene.robot;
  if (!hand.empty()) {
    Arm arm = ArmTo(robot, FindLink(robot, hand));
    SplitDofs(robot, "from '" + robot.links[0].name + "' to --hand '" + hand + "'", &arm);
    return arm;
  }
  // FindArm; when it fails or had to choose between subtrees, an SRDF end effector is preferred.
  std::optional<Arm> found;
  std::string failure;
  try {
    found = FindArm(robot);
    if (found->branch_choices.empty()) return *found;
  } catch (const std::invalid_argument& e) {
    if (!scene.srdf) throw;
    failure = e.what();
  }
  if (scene.srdf) {
    const auto lower = [](std::string x) {
      for (char& c : x) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return x;
    };
    for (const SrdfEndEffector& ee : scene.srdf->end_effectors) {
      const std::string words = lower(ee.name + " " + ee.group + " " + ee.parent_link);
      if (words.find("foot") != std::string::npos || words.find("leg") != std::string::npos ||
          words.find("sole") != std::string::npos) {
        continue;
      }
      const auto it = std::find_if(robot.links.begin(), robot.links.end(),
                                   [&](const Link& l) { return l.name == ee.parent_link; });
      if (it == robot.links.end()) continue;
      const int link = static_cast<int>(it - robot.links.begin());
      Arm arm = ArmTo(robot, link);
      try {
        SplitDofs(robot, "", &arm);
      } catch (const std::invalid_argument&) {
        continue;
      }
      notes->push_back("hand: the parent link '" + ee.parent_link +
                       "' of the SRDF's end_effector '" + ee.name +
                       "' (the tree branches before a serial arm; --hand LINK picks another)");
      return arm;
    }
    if (!found) throw std::invalid_argument(failure);
  }
  std::string choices;
  for (const std::string& c : found->branch_choices)
    choices.append(choices.empty() ? "" : ", ").append(c);
  notes->push_back("hand: '" + robot.links[found->hand].name + "', the arm following the largest " +
                   "subtree at each branch (" + choices + "); --hand LINK picks another");
  return *found;
}

// The links of the subtree below `link` (itself excluded).
std::vector<int> Subtree(const Robot& robot, int link) {
  std::vector<int> out;
  for (size_t l = link + 1; l < robot.links.size(); ++l) {
    for (int p = static_cast<int>(l); p > 0;) {
      const int parent = robot.joints[robot.links[p].parent_joint].parent_link;
      if (parent == link) {
        out.push_back(static_cast<int>(l));
        break;
      }
      if (parent < link) break;
      p = parent;
    }
  }
  return out;
}

Eigen::Matrix3Xd WorldPoints(const LinkPoints& points, const KinematicsData& kin) {
  Eigen::Matrix3Xd p(3, static_cast<Eigen::Index>(points.size()));
  for (size_t i = 0; i < points.size(); ++i)
    p.col(static_cast<Eigen::Index>(i)) = kin.world_from_link[points[i].first] * points[i].second;
  return p;
}

ArmSetup SetUpArm(const RobotScene& scene, const std::string& hand,
                  std::vector<std::string>* notes) {
  const Robot& robot = scene.robot;
  ArmSetup s;
  // The start: DefaultQ, moved into the limits (an SRDF reference pose may lie outside them,
  // and a plan must start inside).
  s.q0 = DefaultQ(scene, notes);
  s.lower = LowerLimits(robot);
  s.upper = UpperLimits(robot);
  const Eigen::VectorXd clamped = s.q0.cwiseMax(s.lower).cwiseMin(s.upper);
  s.start_moved = clamped != s.q0;
  if (s.start_moved) {
    notes->push_back(
        "the default pose lies outside the joint limits: the start is that pose "
        "moved into them (written as start.q)");
    s.q0 = clamped;
  }
  s.arm = ChooseArm(scene, hand, notes);
  KinematicsData kin(robot);
  ForwardKinematics(robot, s.q0, &kin);
  for (int p : s.arm.path) {
    const int j = robot.links[p].parent_joint;
    if (j >= 0 && robot.joints[j].dof >= 0) s.arm_links.push_back(p);
  }
  // The approach axis: from the hand's origin to the centroid of its subtree (fingers), else from
  // the last arm joint to the hand, else the hand's z axis.
  const int hand_link = s.arm.hand;
  const std::vector<int>& links = s.arm_links;
  const Eigen::Vector3d hand_origin = Origin(kin, hand_link);
  const Eigen::Vector3d last_joint = Origin(
      kin, links.back() == hand_link && links.size() > 1 ? links[links.size() - 2] : links.back());
  Eigen::Vector3d tip_world = hand_origin;
  double hand_size = 0.0;
  const std::vector<int> below = Subtree(robot, hand_link);
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
  if (approach.norm() < 1e-6) approach = kin.world_from_link[hand_link].linear().col(2);
  s.approach = approach.normalized();
  s.hand_size = std::max(hand_size, 0.05);
  const Eigen::Matrix3d hand_rot = kin.world_from_link[hand_link].linear();
  s.tool_local = hand_rot.transpose() * s.approach * s.hand_size;
  // Reach: the lengths between consecutive arm joints, plus the hand.
  s.shoulder = Origin(kin, links.front());
  s.reach = s.hand_size;
  for (size_t i = 1; i < links.size(); ++i)
    s.reach += (Origin(kin, links[i]) - Origin(kin, links[i - 1])).norm();
  s.reach += (hand_origin - Origin(kin, links.back())).norm();
  // Link pairs that touch in the start pose (no SRDF, or one that misses them) are disabled, as
  // MoveIt's set-up assistant disables pairs in collision by default; written to the file.
  s.collision_options = scene.collision_options;
  CollisionData self(robot, Environment{}, s.collision_options);
  const CollisionReport report = CheckCollisions(robot, kin, &self, 1000);
  for (const ProximityPair& p : report.pairs) {  // one per shape pair: once per link pair
    std::pair<std::string, std::string> names(robot.links[p.link_a].name,
                                              robot.links[p.link_b].name);
    if (std::find(s.touching.begin(), s.touching.end(), names) != s.touching.end()) continue;
    s.touching.push_back(names);
    s.collision_options.disabled_pairs.push_back(std::move(names));
  }
  if (!s.touching.empty()) {
    notes->push_back(
        base::StrCat(std::to_string(s.touching.size()),
                     " link pair(s) touch in the start pose: disabled (collision.disabled_pairs)"));
  }
  return s;
}

bool AwayFromLimits(const Robot& robot, const ArmSetup& setup, const Eigen::VectorXd& q) {
  const Eigen::VectorXd& lower = setup.lower;
  const Eigen::VectorXd& upper = setup.upper;
  for (int k : setup.arm.arm_dofs) {
    const Joint& joint = robot.joints[robot.dof_joints[k]];
    if (joint.type == JointType::kPrismatic) continue;
    const double room = std::min(0.1, 0.25 * (upper[k] - lower[k]));
    if (q[k] < lower[k] + room || q[k] > upper[k] - room) return false;
  }
  return true;
}

}  // namespace planning::internal
