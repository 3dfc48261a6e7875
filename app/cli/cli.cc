#include "app/cli/cli.h"

#include "app/cli/cmd_grasp_bench.h"
#include "app/cli/command.h"

namespace app {

int RunCommandLine(int argc, char** argv) {
  return RunCommands(
      argc, argv,
      {AddTopologyCommands, AddLinkingCommand, AddDemoCommand, AddRenderCommands, AddGraspCommands,
       AddRobotCommands, AddRobotsCommand, AddScenarioCommand, AddIkCommand, AddPlanCommands,
       AddGraspBenchCommand,  // under `bench`, after bench unwrap
       AddViewCommand});
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
