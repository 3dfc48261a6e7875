// The root of every `topoplan` command line (shared flags, parsing, dispatch) and the end of
// main(): used by the full tool (cli.cc) and by the launcher (launcher.cc).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <iostream>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "base/file_write.h"
#include "base/version.h"

namespace app {

int RunCommands(int argc, char** argv, const std::vector<CommandRegistrar>& registrars) {
  SetCommandLine(argc, argv);
  CLI::App root{
      "topoplan: writhe/winding features, AICO planning, grasp transfer and offscreen rendering.\n"
      "Every subcommand has --help. Exit codes: 0 ok, 1 task failed, 2 bad input, 3 environment."};
  root.require_subcommand(1);
  root.set_version_flag("--version",
                        std::string("topoplan ") + base::Version() + " (" + base::Commit() + ")");
  // -q/-v apply to every command, before or after its name (`topoplan -q plan ...`,
  // `topoplan plan ... -q`).
  root.fallthrough();
  bool quiet = false, verbose = false;
  root.add_flag("-q,--quiet", quiet, "print only results and errors (no progress, no notes)");
  root.add_flag("-v,--verbose", verbose, "also print details (inputs resolved, stages)");
  bool strict = false;
  root.add_flag("--strict", strict,
                "treat every warning as an error (exit 2): an SRDF's unknown names, a pose "
                "outside the limits, ...");
  CommandList commands;
  for (const CommandRegistrar add : registrars) add(&root, &commands);
  StrictIntegerOptions(&root);
  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = root.exit(e);
    return rc == 0 ? kExitOk : kExitBadInput;
  }
  if (quiet && verbose) {
    std::fprintf(stderr, "topoplan: -q/--quiet and -v/--verbose exclude each other\n");
    return kExitBadInput;
  }
  const Verbosity previous = GetVerbosity();  // the demo runs commands in-process
  const bool previous_strict = Strict();
  if (quiet) SetVerbosity(Verbosity::kQuiet);
  if (verbose) SetVerbosity(Verbosity::kVerbose);
  if (strict) SetStrict(true);
  for (const Command& c : commands) {
    if (c.sub->parsed()) {
      // The full command path in messages ("scenario new", "robots check").
      std::string name = c.sub->get_name();
      for (const CLI::App* a = c.sub->get_parent(); a != nullptr && a->get_parent() != nullptr;
           a = a->get_parent()) {
        name = std::string(a->get_name()).append(" ").append(name);
      }
      const int rc = RunGuarded(name, c.run);
      SetVerbosity(previous);
      SetStrict(previous_strict);
      return rc;
    }
  }
  return kExitBadInput;
}

void BufferStdout() {
  static char buffer[1 << 20];
  std::setvbuf(stdout, buffer, isatty(STDOUT_FILENO) ? _IOLBF : _IOFBF, sizeof buffer);
}

int FinishMain(int rc) {
  // Every write is checked, standard output too: JSON sent to a full disk or a closed pipe is a
  // failure, not a success (exit 3, the reason named).
  errno = 0;
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout.flush();
  if (failed) {
    const int err = errno != 0 ? errno : EIO;
    std::fprintf(stderr, "topoplan: cannot write to standard output: %s\n",
                 base::ErrnoText(err).c_str());
    return rc == kExitOk || rc == kExitFailed ? kExitEnvironment : rc;
  }
  return rc;
}

}  // namespace app
