// topoplan: topology-based motion planning and grasp transfer, with offscreen rendering.
#include <cerrno>
#include <cstdio>
#include <iostream>

#include <unistd.h>

#include "app/cli/cli.h"
#include "app/cli/command.h"
#include "base/file_write.h"

int main(int argc, char** argv) {
  // Buffered until the end (1 MiB, unless a terminal), so that a failing write is seen by the
  // final flush below with its reason (ENOSPC, EPIPE, EBADF).
  static char buffer[1 << 20];
  std::setvbuf(stdout, buffer, isatty(STDOUT_FILENO) ? _IOLBF : _IOFBF, sizeof buffer);
  const int rc = app::RunCommandLine(argc, argv);
  // Every write is checked, standard output too: JSON sent to a full disk or a closed pipe is a
  // failure, not a success (exit 3, the reason named).
  errno = 0;
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout.flush();
  if (failed) {
    const int err = errno != 0 ? errno : EIO;
    std::fprintf(stderr, "topoplan: cannot write to standard output: %s\n",
                 base::ErrnoText(err).c_str());
    return rc == app::kExitOk || rc == app::kExitFailed ? app::kExitEnvironment : rc;
  }
  return rc;
}
