// Fuzz targets of the formats read by app/: scene JSON, viewer scripts and command-line flags.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "visualize/figures.h"
#include "app/cli/io.h"
#include "planning/motion/robot_scene.h"
#include "visualize/scene_file.h"
#include "app/viewer/session.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/motion/planner.h"
#include "render/offscreen_context.h"
#include "tests/fuzz/fuzz_targets.h"
#include "base/file_read.h"
#include "base/numbers.h"

namespace topoplan_fuzz {
namespace {

// The whole command line, parsed as main() parses it but without running the command.
void ParseCommandLine(const std::string& text) {
  std::vector<std::string> args;
  std::string token;
  for (char c : text) {
    if (c == '\n' || c == '\0') {
      args.push_back(token);
      token.clear();
    } else {
      token += c;
    }
  }
  args.push_back(token);
  CLI::App root{"topoplan"};
  root.require_subcommand(1);
  app::CommandList commands;
  // Every command of app_core; `demo` (app_cli) and `view` (app_ui) are left out so that the
  // fuzz programs do not link the window libraries.
  app::AddTopologyCommands(&root, &commands);
  app::AddRenderCommands(&root, &commands);
  app::AddGraspCommands(&root, &commands);
  app::AddRobotCommands(&root, &commands);
  app::AddPlanCommands(&root, &commands);
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last-first
  try {
    root.parse(args);
  } catch (const CLI::ParseError&) {
  }
}

}  // namespace

int SceneJson(const uint8_t* data, size_t size) {
  try {
    const nlohmann::json doc = base::ParseJsonText(Text(data, size), "fuzz.json");
    visualize::ParseSceneJson(doc, "fuzz.json", AssetPath("scenes"));
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int Script(const uint8_t* data, size_t size) {
  try {
    app::ParseScript(WriteInput(data, size, "script.txt"));
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

int Flags(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text = Text(data + 1, size - 1);
  try {
    switch (data[0] < 0x80 ? data[0] % 9 : 9) {
      case 0:
        base::ParseNumberList(text, "--object");
        break;
      case 1:
        base::ParseNumberList(text, "--camera", 7, 1e6);
        break;
      case 2: {
        std::string value = text;
        app::FiniteIn(0.0, 2000.0)(value);
        break;
      }
      case 3: {
        int w = 0, h = 0;
        visualize::ParseImageSize(text, "--size", &w, &h);
        break;
      }
      case 4:
        planning::ParseQ(TinyArm(), text);
        break;
      case 5:
        app::ParseFlag("--planner", [&] { return planning::ParsePlanner(text); });
        break;
      case 6:
        app::ParseFlag("--method", [&] { return planning::ParseTransferMethod(text); });
        break;
      case 7:
        render::ParseGlBackend(text, "--gl");
        break;
      case 8:
        base::ParseFiniteDouble(text);
        break;
      default:
        ParseCommandLine(text);
    }
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

}  // namespace topoplan_fuzz
