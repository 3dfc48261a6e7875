#include "app/cli/cli.h"

#include <CLI/CLI.hpp>

#include "app/cli/command.h"

namespace app {

int RunCommandLine(int argc, char** argv) {
  CLI::App root{
      "topoplan: writhe/winding features, AICO planning, grasp transfer and offscreen rendering.\n"
      "Every subcommand has --help. Exit codes: 0 ok, 1 task failed, 2 bad input, 3 environment."};
  root.require_subcommand(1);
  root.set_version_flag("--version", "topoplan 0.1.0");
  CommandList commands;
  AddTopologyCommands(&root, &commands);
  AddDemoCommand(&root, &commands);
  AddRenderCommands(&root, &commands);
  AddGraspCommands(&root, &commands);
  AddRobotCommands(&root, &commands);
  AddPlanCommands(&root, &commands);
  AddViewCommand(&root, &commands);
  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = root.exit(e);
    return rc == 0 ? kExitOk : kExitBadInput;
  }
  for (const Command& c : commands) {
    if (c.sub->parsed()) return RunGuarded(c.sub->get_name(), c.run);
  }
  return kExitBadInput;
}

int RunCommandLine(const std::vector<std::string>& args) {
  std::vector<std::string> storage;
  storage.reserve(args.size() + 1);
  storage.push_back("topoplan");
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  return RunCommandLine(static_cast<int>(storage.size()), argv.data());
}

}  // namespace app
