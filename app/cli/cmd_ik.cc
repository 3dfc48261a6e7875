// `topoplan ik`: joint values that put a point of a link at a world position (and a link axis
// along a world direction), by planning/robot/ik.h.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "app/cli/robot_flags.h"
#include "base/numbers.h"
#include "planning/collision/collision.h"
#include "planning/motion/robot_scene.h"
#include "planning/robot/ik.h"

namespace app {
namespace {

using Json = nlohmann::ordered_json;

struct IkArgs {
  std::string urdf, link, position, offset, axis, q, pose;
  std::vector<std::string> frozen;
  planning::RobotInputOptions input;
  int starts = 8, iterations = 200;
  long long seed = 0;
  double tolerance = 1e-5, axis_tolerance = 1e-5;
  bool json = false, check_collision = false;
};

Eigen::Vector3d Vector3(const std::string& text, const std::string& flag) {
  const std::vector<double> v = base::ParseNumberList(text, flag, 3);
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

// "LOCAL:WORLD": LOCAL is x, y, z, -x, -y, -z or three numbers; WORLD three numbers.
planning::IkAxis ParseAxis(const std::string& text) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) {
    throw std::invalid_argument("--axis: expected LOCAL:WORLD, e.g. z:1,0,0 (got '" + text + "')");
  }
  const std::string local = text.substr(0, colon);
  planning::IkAxis axis;
  const std::string names[] = {"x", "y", "z"};
  bool named = false;
  for (int i = 0; i < 3; ++i) {
    if (local == names[i] || local == "+" + names[i] || local == "-" + names[i]) {
      axis.local = Eigen::Vector3d::Unit(i) * (local[0] == '-' ? -1.0 : 1.0);
      named = true;
    }
  }
  if (!named) axis.local = Vector3(local, "--axis (link axis)");
  axis.world = Vector3(text.substr(colon + 1), "--axis (world direction)");
  if (axis.local.norm() < 1e-12 || axis.world.norm() < 1e-12) {
    throw std::invalid_argument("--axis: directions must be non-zero");
  }
  return axis;
}

std::string QText(const Eigen::VectorXd& q) {
  std::string out;
  for (int k = 0; k < q.size(); ++k) {
    if (k) out.append(",");
    out.append(base::FormatShortest(q[k]));
  }
  return out;
}

int RunIk(const IkArgs& a) {
  planning::RobotScene scene = planning::LoadRobotScene(a.urdf, a.input);
  const planning::Robot& robot = scene.robot;
  std::vector<std::string> warnings = scene.warnings;
  planning::IkProblem problem;
  planning::IkTarget target;
  target.link = ParseFlag("--link", [&] { return planning::FindLink(robot, a.link); });
  target.position = Vector3(a.position, "--position");
  if (!a.offset.empty()) target.offset = Vector3(a.offset, "--offset");
  if (!a.axis.empty()) target.axis = ParseAxis(a.axis);
  problem.targets.push_back(target);
  // The start: --q / --pose, else what `fk` shows without them (moved into the limits by SolveIk).
  std::vector<std::string> notes = scene.notes;
  problem.seed = planning::ChooseQ(scene, a.q, a.pose, &warnings, &notes);
  // --frozen: joint names, or SRDF group names (e.g. "gripper": every joint the group moves).
  problem.frozen_dofs = ParseFlag("--frozen", [&] {
    std::vector<int> dofs;
    std::vector<std::string> joints;
    for (const std::string& name : a.frozen) {
      bool group = false;
      if (scene.srdf) {
        for (const planning::SrdfGroup& g : scene.srdf->groups) group = group || g.name == name;
      }
      if (!group) {
        joints.push_back(name);
        continue;
      }
      for (int k : planning::GroupDofs(robot, *scene.srdf, name)) dofs.push_back(k);
    }
    for (int k : planning::DofIndices(robot, joints)) dofs.push_back(k);
    std::sort(dofs.begin(), dofs.end());
    dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
    return dofs;
  });
  ReportWarnings(warnings);
  ReportNotes(notes);

  planning::IkOptions options;
  options.starts = a.starts;
  options.max_iterations = a.iterations;
  options.random_seed = static_cast<std::uint32_t>(a.seed);
  options.position_tolerance = a.tolerance;
  options.axis_tolerance = a.axis_tolerance;
  std::unique_ptr<planning::CollisionData> coll;
  planning::KinematicsData check_kin(robot);
  if (a.check_collision) {
    coll = std::make_unique<planning::CollisionData>(robot, planning::CollisionEnvironment(scene),
                                                     scene.collision_options);
    options.is_valid = [&](const Eigen::VectorXd& q) {
      planning::ForwardKinematics(robot, q, &check_kin);
      return !planning::InCollision(robot, check_kin, coll.get());
    };
  }
  planning::IkData data(robot);
  const planning::IkResult r = planning::SolveIk(robot, problem, options, &data);
  planning::ForwardKinematics(robot, r.q, &check_kin);
  const Eigen::Vector3d reached = check_kin.world_from_link[target.link] * target.offset;

  if (a.json) {
    Json out;
    out["robot"] = robot.name;
    out["link"] = a.link;
    out["status"] = planning::IkStatusName(r.status);
    out["joints"] = planning::DofNames(robot);
    out["q"] = std::vector<double>(r.q.data(), r.q.data() + r.q.size());
    out["position"] = {reached.x(), reached.y(), reached.z()};
    out["position_error"] = r.position_error;
    out["axis_error"] = r.axis_error;
    out["iterations"] = r.iterations;
    out["starts"] = r.starts;
    out["start"] = r.start;
    out["collision_checked"] = a.check_collision;
    out["rejected"] = r.rejected;
    std::cout << out.dump() << "\n";
  } else {
    std::printf("%s: %s (link %s, start %d; %d of %d starts, %d iterations", robot.name.c_str(),
                planning::IkStatusName(r.status), a.link.c_str(), r.start, r.starts, a.starts,
                r.iterations);
    if (a.check_collision) std::printf("; %d in collision", r.rejected);
    std::printf(")\n");
    std::printf("position error %.3g m, axis error %.3g rad; reached %.6f %.6f %.6f\n",
                r.position_error, r.axis_error, reached.x(), reached.y(), reached.z());
    std::printf("joints (q order):");
    for (const std::string& n : planning::DofNames(robot)) std::printf(" %s", n.c_str());
    std::printf("\nq %s\n", QText(r.q).c_str());
  }
  return r.status == planning::IkStatus::kSolved ? kExitOk : kExitFailed;
}

}  // namespace

void AddIkCommand(CLI::App* root, CommandList* commands) {
  auto a = std::make_shared<IkArgs>();
  CLI::App* ik = root->add_subcommand(
      "ik", "Inverse kinematics: joint values that put a link point at a world position");
  ik->add_option("ROBOT", a->urdf, "robot URDF file (or a scene JSON with \"robot\")")->required();
  ik->add_option("--link", a->link, "the link that must reach the target")->required();
  ik->add_option("--position", a->position, "target position x,y,z [m], world frame")->required();
  ik->add_option("--offset", a->offset,
                 "the point on the link x,y,z [m], link frame (default: its origin 0,0,0)")
      ->check(NonEmpty());
  ik->add_option("--axis", a->axis,
                 "approach axis LOCAL:WORLD: the link axis LOCAL (x, y, z, -x, -y, -z or a,b,c) "
                 "along the world direction WORLD (a,b,c), e.g. z:1,0,0")
      ->check(NonEmpty());
  ik->add_option("--q", a->q,
                 "start configuration v1,v2,... (rad / m) in the `fk` joint order (default: the "
                 "configuration `fk` shows without --q; values outside the limits are moved "
                 "into them); --frozen joints keep it")
      ->check(NonEmpty());
  AddRobotInputFlags(ik, &a->input, &a->pose);
  ik->add_option("--frozen", a->frozen,
                 "joints held at their start value, comma-separated joint names or SRDF group "
                 "names (e.g. gripper)")
      ->delimiter(',')
      ->check(NonEmpty());
  IntIn(ik->add_option("--starts", a->starts,
                       "starts: the start configuration, then random ones in the limits "
                       "(default 8)"),
        1, 100000);
  IntIn(ik->add_option("--iterations", a->iterations,
                       "Levenberg-Marquardt iterations per start (default 200)"),
        1, 1000000);
  IntIn(ik->add_option("--seed", a->seed, "random seed of the random starts (default 0)"), 0,
        4294967295LL);
  ik->add_option("--tolerance", a->tolerance, "position tolerance [m] (default 1e-5)")
      ->check(FiniteIn(1e-12, 10.0));
  ik->add_option("--axis-tolerance", a->axis_tolerance, "axis tolerance [rad] (default 1e-5)")
      ->check(FiniteIn(1e-12, 3.2));
  ik->add_flag("--check-collision", a->check_collision,
               "accept only collision-free solutions (self-collision and the scene's objects; "
               "the SRDF's disabled pairs are skipped): a solution in collision sends the "
               "solver to the next start");
  ik->add_flag("--json", a->json,
               "print {\"robot\", \"link\", \"status\", \"joints\", \"q\", \"position\", "
               "\"position_error\", \"axis_error\", \"iterations\", \"starts\", ...}");
  ik->footer(
      "Damped least squares (Levenberg-Marquardt) inside the joint limits, from the start\n"
      "configuration and then from random ones (deterministic for a --seed), stopping at the\n"
      "first solution (docs/robots.md#inverse-kinematics). q is printed in the `fk` joint order,\n"
      "ready for `fk --q` or a scenario's final_pose. Status: solved (exit 0); not_reached (no\n"
      "start met the tolerances: the closest q found, exit 1); invalid (reached, but every\n"
      "solution was in collision, exit 1). Bad input exits 2.");
  commands->push_back({ik, [a]() { return RunIk(*a); }});
}

}  // namespace app
