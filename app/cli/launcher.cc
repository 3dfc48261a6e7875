// topoplan: the command users run. A process that links the renderer (OSMesa with LLVM), the
// physics engines, the planners and the window libraries spends ~30 ms loading them before
// main(); `linking` needs none of them. This small program runs such commands itself and
// replaces itself (execv) by topoplan-full, the whole tool, for every other command line, with the
// arguments unchanged. docs/architecture.md: the launcher.
#include <limits.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "app/cli/command.h"

namespace {

// The command a command line names: its first argument that is not a root flag (-q, -v, --strict
// and their long forms take no value); "" when there is none (--help, --version, nothing).
std::string_view CommandName(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "-q" || a == "--quiet" || a == "-v" || a == "--verbose" || a == "--strict") continue;
    return a.starts_with("-") ? std::string_view() : a;
  }
  return {};
}

// <directory of this executable>/topoplan-full.
std::string FullToolPath() {
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return "topoplan-full";
  std::string path(self, static_cast<size_t>(n));
  path.erase(path.rfind('/') + 1);
  return path + "topoplan-full";
}

}  // namespace

int main(int argc, char** argv) {
  if (CommandName(argc, argv) == "linking") {
    app::BufferStdout();
    return app::FinishMain(app::RunCommands(argc, argv, {app::AddLinkingCommand}));
  }
  const std::string full = FullToolPath();
  execv(full.c_str(), argv);
  const int err = errno;
  std::fprintf(stderr,
               "topoplan: cannot run %s (%s); it is installed next to topoplan and runs every "
               "command but `linking`\n",
               full.c_str(), std::strerror(err));
  return app::kExitEnvironment;
}
