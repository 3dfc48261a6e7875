#include "app/cli/command.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "app/cli/io.h"

namespace app {

std::string PrintableMessage(const std::string& text, std::size_t max_bytes) {
  std::string out;
  const std::size_t n = std::min(text.size(), max_bytes);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > n) out += "... (" + std::to_string(text.size() - n) + " more bytes)";
  return out;
}

namespace {

// One line on stderr, whatever bytes the message holds (a NUL from an input file no longer cuts
// it short, a 60 MB line from a script is not echoed whole).
void PrintError(const std::string& name, const char* kind, const char* what) {
  const std::string line =
      "topoplan " + name + ": " + kind + PrintableMessage(what ? what : "", 2000) + "\n";
  std::fwrite(line.data(), 1, line.size(), stderr);
}

}  // namespace

int RunGuarded(const std::string& name, const std::function<int()>& run) {
  try {
    return run();
  } catch (const StopRequested& e) {  // a command that does not report its own stop
    PrintError(name, "", e.what());
    return e.timeout ? kExitFailed : kExitInterrupted;
  } catch (const EnvironmentError& e) {  // base::EnvironmentError: context, asset, write
    PrintError(name, "environment error: ", e.what());
    return kExitEnvironment;
  } catch (const std::exception& e) {
    PrintError(name, "error: ", e.what());
    return kExitBadInput;
  }
}

}  // namespace app
