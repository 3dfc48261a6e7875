// Subcommand plumbing shared by every `topoplan` command: exit codes, error kinds, registration.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/errors.h"
#include "base/json_reader.h"

namespace app {

// Exit codes: 0 success; 1 ran but the task failed (no path, not converged, unstable
// grasp, images differ) or hit its --timeout; 2 bad input or usage; 3 environment error (no GL
// context, missing asset); 130 stopped by SIGINT/SIGTERM (app/cli/io.h StopCheck).
enum ExitCode : int {
  kExitOk = 0,
  kExitFailed = 1,
  kExitBadInput = 2,
  kExitEnvironment = 3,
  kExitInterrupted = 130
};

// Environment problems (no GL context, no system font, a missing installed asset): exit code 3.
// The one class is base's (render's ContextError, a GL context that fails, derives from it); app
// code throws and RunGuarded catches it under this name. Every other exception that reaches
// RunGuarded (std::invalid_argument from loaders, ...) is bad input: exit code 2.
using base::EnvironmentError;

// A registered subcommand: `run` is called when `sub` was parsed and returns the exit code.
struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;
};
using CommandList = std::vector<Command>;
// Adds one command family to the root (the Add*Command functions below).
using CommandRegistrar = void (*)(CLI::App* root, CommandList* commands);

// Parses argv with the root flags every command shares (-q, -v, --strict, --version) and the
// commands of `registrars`, and runs the one named (RunGuarded); returns the exit code. The
// full command line (cli.h RunCommandLine) passes every family; the launcher (cli/launcher.cc)
// only the ones that need no renderer, physics or planner.
int RunCommands(int argc, char** argv, const std::vector<CommandRegistrar>& registrars);

// Start of main(): standard output buffered until the end (1 MiB, unless a terminal), so that a
// failing write is seen by FinishMain's flush with its reason.
void BufferStdout();
// End of main(): flushes standard output and returns `rc`, or 3 (environment) with the reason on
// stderr when a write failed (ENOSPC, EPIPE, EBADF) and rc was 0 or 1.
int FinishMain(int rc);

// Registration functions, one per command family (app/cmd_*.cc).
void AddTopologyCommands(CLI::App* root, CommandList* commands);  // writhe, winding
void AddLinkingCommand(CLI::App* root, CommandList* commands);    // linking
void AddDemoCommand(CLI::App* root, CommandList* commands);       // demo
void AddRenderCommands(CLI::App* root, CommandList* commands);    // render, heatmap, diff
void AddGraspCommands(CLI::App* root, CommandList* commands);     // grasp synthesize|transfer
void AddRobotCommands(CLI::App* root, CommandList* commands);     // fk, check
void AddRobotsCommand(CLI::App* root, CommandList* commands);     // robots check
void AddScenarioCommand(CLI::App* root, CommandList* commands);   // scenario new
void AddIkCommand(CLI::App* root, CommandList* commands);         // ik
void AddPlanCommands(CLI::App* root, CommandList* commands);      // plan (then AddBenchCommands)
void AddBenchCommands(CLI::App* root, CommandList* commands);     // bench unwrap (cmd_bench.cc)

// Shared by `plan` and `bench unwrap` (cmd_plan.cc): the --aico-stop help, its value ("solved" →
// true, "converged" → false, "" → the scenario's), and "aico | rrt | ..." of this build.
extern const char* const kAicoStopHelp;
std::optional<bool> ParseAicoStop(const std::string& text);
std::string PlannerChoices();
void AddViewCommand(CLI::App* root, CommandList* commands);  // view (app/viewer/cmd_view.cc)

// Calls parse() and prefixes any std::invalid_argument it throws with the flag's name
// ("--method: unknown transfer method 'x' (...)"): the library names values, the CLI names flags.
template <typename F>
auto ParseFlag(const std::string& flag, F&& parse) -> decltype(parse()) {
  return base::PrefixErrors(flag, std::forward<F>(parse));
}

// Runs `run`, mapping exceptions to exit codes and printing "topoplan <name>: error: ..." to
// stderr.
// `text` safe to print: control bytes (a NUL included) as \xNN, at most `max_bytes` bytes and then
// "... (N more bytes)".
std::string PrintableMessage(const std::string& text, std::size_t max_bytes);

int RunGuarded(const std::string& name, const std::function<int()>& run);

}  // namespace app
