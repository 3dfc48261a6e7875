// topoplan-full: the whole tool (every command). Users run `topoplan`, the launcher
// (launcher.cc), which runs the commands that need no renderer, physics or planner itself and
// hands every other command line to this program unchanged.
#include "app/cli/cli.h"
#include "app/cli/command.h"

int main(int argc, char** argv) {
  app::BufferStdout();
  return app::FinishMain(app::RunCommandLine(argc, argv));
}
