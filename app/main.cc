// topoplan: topology-based motion planning and grasp transfer, with offscreen rendering.
#include <CLI/CLI.hpp>

#include "app/command.h"

int main(int argc, char** argv) {
  CLI::App root{
      "topoplan: writhe/winding features, AICO planning, grasp transfer and offscreen rendering.\n"
      "Every subcommand has --help. Exit codes: 0 ok, 1 task failed, 2 bad input, 3 environment."};
  root.require_subcommand(1);
  root.set_version_flag("--version", "topoplan 0.1.0");
  app::CommandList commands;
  app::AddTopologyCommands(&root, &commands);
  app::AddDemoCommand(&root, &commands);
  app::AddRenderCommands(&root, &commands);
  app::AddGraspCommands(&root, &commands);
  app::AddRobotCommands(&root, &commands);
  app::AddPlanCommands(&root, &commands);
  app::AddViewCommand(&root, &commands);
  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = root.exit(e);
    return rc == 0 ? app::kExitOk : app::kExitBadInput;
  }
  for (const app::Command& c : commands) {
    if (c.sub->parsed()) return app::RunGuarded(c.sub->get_name(), c.run);
  }
  return app::kExitBadInput;
}
