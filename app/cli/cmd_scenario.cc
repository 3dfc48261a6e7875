// `topoplan scenario new`: a working scenario for a robot (planning/motion/scenario_new.h).
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "base/file_write.h"
#include "planning/motion/scenario_new.h"

namespace app {
namespace {

struct NewArgs {
  std::string robot, output;
  planning::NewScenarioOptions options;
  long long seed = 0;
};

}  // namespace

void AddScenarioCommand(CLI::App* root, CommandList* commands) {
  CLI::App* scenario = root->add_subcommand("scenario", "Make scenario files for your robot");
  scenario->require_subcommand(1);
  auto a = std::make_shared<NewArgs>();
  CLI::App* make = scenario->add_subcommand(
      "new", "Write a working scenario for any robot: hand, ring, goal pose by IK, box, success");
  make->add_option("--robot", a->robot, "robot URDF")->required();
  make->add_option("--task", a->options.task,
                   "ring: reach through a ring with a writhe target (default); reach: reach a "
                   "point in front of the arm inside a box; unwrap: start hooked around a pole, "
                   "unwrap (writhe -> 0) and reach a target")
      ->check(CLI::IsMember({"ring", "reach", "unwrap"}));
  make->add_option("--object", a->options.object,
                   "the ring's URDF (default assets/objects/ring.urdf; needs a closed chain "
                   "'loop'), or with --task unwrap the pole's (default assets/objects/pole.urdf; "
                   "needs a chain 'axis')")
      ->check(NonEmpty());
  make->add_option("--package-path", a->options.package_paths,
                   "root for package:// URIs (repeatable)")
      ->check(NonEmpty());
  make->add_option("--srdf", a->options.srdf, "the robot's SRDF (default: found as `check` does)")
      ->check(NonEmpty());
  make->add_option("--hand", a->options.hand,
                   "the hand link; the arm is the path from the root to it (default: where the "
                   "tree branches into fingers, else the SRDF's end_effector)")
      ->check(NonEmpty());
  make->add_option("--name", a->options.name, "scenario name (default ROBOT_TASK)")
      ->check(NonEmpty());
  IntIn(make->add_option("--seed", a->seed,
                         "seed of the inverse kinematics' random starts (unwrap: of the sampled "
                         "configurations)"),
        0, 4294967295LL);
  make->add_option("-o,--output", a->output, "the scenario file to write (.json)")->required();
  make->footer(
      "Finds the hand (where the arm's kinematic tree branches into fingers, or its last link),\n"
      "a tool point ahead of it, a hand chain, places the ring in front of the first arm joint\n"
      "where inverse kinematics finds a collision-free goal with the hand chain through the\n"
      "ring, and writes the scenario with a box, reach, collision and joint-limit tasks and the\n"
      "success criteria inside_box + through_loop. --task unwrap instead samples a start hooked\n"
      "around a pole (winding >= 0.15 turns) and an unwrapped goal near it, with the tasks and\n"
      "success criteria of assets/scenarios/unwrap.json. Keys starting with // in the file say\n"
      "what to edit. Then: topoplan plan FILE -o out. Exit 0 written, 2 bad input or no placement\n"
      "found.");
  commands->push_back({make, [a]() {
                         base::CheckOutputFile(a->output, "--output", {a->robot});
                         a->options.seed = static_cast<std::uint32_t>(a->seed);
                         const planning::NewScenario s =
                             planning::MakeNewScenario(a->robot, a->options);
                         base::WriteFileAtomic(a->output, s.json.dump(2) + "\n");
                         ReportNotes(s.notes);
                         Note("wrote %s (hand '%s'; plan it with: topoplan plan %s -o DIR)",
                              a->output.c_str(), s.hand_link.c_str(), a->output.c_str());
                         return kExitOk;
                       }});
}

}  // namespace app
