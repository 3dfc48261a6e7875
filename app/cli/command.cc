#include "app/cli/command.h"

#include <cstdio>
#include <exception>

#include "app/cli/io.h"

namespace app {

int RunGuarded(const std::string& name, const std::function<int()>& run) {
  try {
    return run();
  } catch (const StopRequested& e) {  // a command that does not report its own stop
    std::fprintf(stderr, "topoplan %s: %s\n", name.c_str(), e.what());
    return e.timeout ? kExitFailed : kExitInterrupted;
  } catch (const EnvironmentError& e) {  // render::EnvironmentError and its ContextError
    std::fprintf(stderr, "topoplan %s: environment error: %s\n", name.c_str(), e.what());
    return kExitEnvironment;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "topoplan %s: error: %s\n", name.c_str(), e.what());
    return kExitBadInput;
  }
}

}  // namespace app
