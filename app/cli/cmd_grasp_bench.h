// `topoplan bench grasp` (issue 36): registered under the `bench` command, which it creates if no
// other benchmark has yet.
#pragma once

#include "app/cli/command.h"

namespace app {

void AddGraspBenchCommand(CLI::App* root, CommandList* commands);

}  // namespace app
