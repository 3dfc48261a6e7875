// topoplan-full: the whole tool (every command). Users run `topoplan`, the launcher
// (launcher.cc), which runs the commands that need no renderer, physics or planner itself and
// hands every other command line to this program unchanged.
#include <unistd.h>

#include <cstdio>

#include "app/cli/cli.h"
#include "app/cli/command.h"

int main(int argc, char** argv) {
  // Buffered until the end (1 MiB, unless a terminal), so that a failing write is seen by the
  // final flush with its reason.
  static char buffer[1 << 20];
  std::setvbuf(stdout, buffer, isatty(STDOUT_FILENO) ? _IOLBF : _IOFBF, sizeof buffer);
  return app::FinishMain(app::RunCommandLine(argc, argv));
}
