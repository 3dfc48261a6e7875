// The arm of `scenario new` (internal/scenario_arm.h).
#include "planning/motion/internal/scenario_arm.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <stdexcept>

namespace planning::internal {
namespace {
// A subtree reaching this far (m) from where the tree branches is an arm, not a finger (FindArm).
constexpr double kArmReach = 0.2;

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
  for (;;) {
    std::vector<int> moving;
    for (int c : children[l]) {
      if (movable[c] > 0 || robot.joints[robot.links[c].parent_joint].dof >= 0) moving.push_back(c);
    }
    if (moving.empty()) break;
    if (moving.size() > 1) {
      // A branch: fingers (subtrees reaching less than kArmReach from this link in the zero
      // pose) make this link the hand; else the walk follows the long subtree with the most
      // movable joints (a humanoid's torso rather than a leg, then one of its arms).
      int best = -1, best_count = -1;
      for (int c : moving) {
        double r = 0.0;
        for (int d = c; d < nl; ++d) {  // d in c's subtree: walk up until at or above c
          int a = d;
          while (a > c) a = robot.joints[robot.links[a].parent_joint].parent_link;
          if (a == c) r = std::max(r, (Origin(kin, d) - Origin(kin, l)).norm());
        }
        const int count = movable[c] + (robot.joints[robot.links[c].parent_joint].dof >= 0 ? 1 : 0);
        if (r >= kArmReach && count > best_count) best = c, best_count = count;
      }
      if (best < 0) break;
      arm.branch_choices.push_back(robot.links[l].name + " → " + robot.links[best].name);
      moving = {best};
    }
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

}  // namespace planning::internal
