// The whole `topoplan` command line as a function: main() of topoplan-full (the launcher hands it
// every command it does not run itself) and the demo (which runs other commands in-process,
// exactly as a user would type them) both go through it.
#pragma once

#include <string>
#include <vector>

namespace app {

// Parses and runs one command line (argv[0] is the program name); returns the exit code
// (0 ok, 1 task failed, 2 bad input or usage, 3 environment).
int RunCommandLine(int argc, char** argv);

// The same for a list of arguments without the program name, e.g. {"plan", "unwrap", "-o", "d"}.
int RunCommandLine(const std::vector<std::string>& args);

}  // namespace app
