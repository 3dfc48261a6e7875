// `topoplan view`: the interactive window, or its headless twin with --screenshot.
#include <memory>
#include <stdexcept>

#include "app/command.h"
#include "app/figures.h"
#include "app/ui/viewer.h"

namespace app {

void AddViewCommand(CLI::App* root, CommandList* commands) {
  auto o = std::make_shared<ui::ViewerOptions>();
  auto size = std::make_shared<std::string>("1280x720");
  CLI::App* view = root->add_subcommand(
      "view", "Interactive viewer (GLFW + Dear ImGui); headless with --screenshot");
  view->add_option("SCENARIO", o->scenario,
                   "scenario name (assets/scenarios/NAME.json) or path, URDF or scene JSON");
  view->add_option("--screenshot", o->screenshot,
                   "run headless (OSMesa) and write the final frame, UI included, to this PNG");
  view->add_option("--script", o->script,
                   "command file: load, plan, step, play, pause, seek T, joint I A, reset, toggle "
                   "NAME, planner P, seed N, camera YAW PITCH DIST, frames N, click WIDGET, "
                   "screenshot PNG, quit");
  view->add_flag("--headless", o->headless, "no window even without --screenshot");
  AddRobotInputFlags(view, &o->robot_input, nullptr);
  view->add_flag("!--no-overlay", o->overlay, "headless frames without the UI panels");
  view->add_option("--size", *size, "window / frame size WxH")->capture_default_str();
  view->add_option("--exit-after", o->exit_after, "close the window after N frames (tests)");
  view->add_flag("--print-widgets", o->print_widgets,
                 "print the screen rectangles of the named widgets (for scripted clicks)");
  view->footer(
      "Mouse: left drag orbits, right drag pans, wheel zooms. Buttons: Plan, Step sweep (shows the "
      "next AICO sweep), Play/Pause and the timeline scrubber; joint sliders move the robot.");
  commands->push_back({view, [o, size]() {
                         ParseImageSize(*size, "--size", &o->width, &o->height);
                         if (o->width < 64 || o->height < 64) {
                           throw std::invalid_argument(
                               "--size: the viewer needs each side >= 64, got '" + *size + "'");
                         }
                         return ui::RunViewer(*o);
                       }});
}

}  // namespace app
