// `topoplan view`: the interactive window, or its headless twin with --screenshot.
#include <memory>
#include <stdexcept>

#include "app/cli/command.h"
#include "visualize/figures.h"
#include "app/cli/io.h"
#include "app/cli/robot_flags.h"
#include "app/viewer/viewer.h"

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
  view->add_option(
      "--script", o->script,
      "command file, one per line: load PATH, plan [async], step [N], wait, cancel, "
      "rrt_step N, sim_step N, sim_phase [N], move OBJECT X Y Z, status FILE, play, pause, seek "
      "SECONDS, joint I A, reset, toggle NAME, planner P, seed N, damping LAMBDA (AICO's initial "
      "damping), camera YAW PITCH "
      "DIST [TX TY TZ], frames N, click WIDGET, screenshot PNG, grasp NAME METHOD, "
      "grasp_step N, quit");
  view->add_flag("--headless", o->headless, "no window even without --screenshot");
  AddRobotInputFlags(view, &o->robot_input, nullptr);
  view->add_flag("!--no-overlay", o->overlay, "headless frames without the UI panels");
  view->add_option("--size", *size, "window / frame size WxH")->capture_default_str();
  view->add_option("--exit-after", o->exit_after, "close the window after N frames (tests)");
  view->add_option("--preview-interval", o->preview_interval_ms,
                   "while a plan or simulation runs, re-render the 3-D scene at most every MS "
                   "milliseconds (panels and progress still update every frame)")
      ->capture_default_str();
  view->add_flag("--print-widgets", o->print_widgets,
                 "print the screen rectangles of the named widgets (for scripted clicks)");
  view->footer(
      "Mouse: left drag orbits, right drag pans, wheel zooms, Shift + left drag moves the chosen "
      "object (the arm re-plans from where it is as the object moves). Buttons: Plan (on a worker "
      "thread; the window keeps drawing), "
      "Step sweep (runs one more real AICO sweep), Cancel, Play/Pause and the timeline scrubber "
      "(seconds); joint sliders move the robot; the grasp panel's Step and Step phase advance the "
      "live ODE test by 20 ms or to the end of its current phase. The 3-D scene is rendered "
      "again only when it changes (at most every --preview-interval ms while the worker runs).");
  commands->push_back({view, [o, size, view]() {
                         // Checked before the window opens ("" is refused, not "no screenshot").
                         if (view->count("--screenshot") > 0) {
                           base::CheckOutputFile(o->screenshot, "--screenshot");
                         }
                         visualize::ParseImageSize(*size, "--size", &o->width, &o->height);
                         if (o->width < 64 || o->height < 64) {
                           throw std::invalid_argument(
                               "--size: the viewer needs each side >= 64, got '" + *size + "'");
                         }
                         return ui::RunViewer(*o);
                       }});
}

}  // namespace app
