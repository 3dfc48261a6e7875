// The interactive window (GLFW + Dear ImGui) and its headless twin (OSMesa/EGL), one code path:
// both build the same panels, apply the same Commands to a Session and draw the same frame with
// the same Renderer; the window only adds mouse input and a swap chain.
#pragma once

#include <string>

#include "planning/motion/robot_scene.h"

namespace app::ui {

struct ViewerOptions {
  std::string scenario;    // scenario name/path, URDF or scene JSON ("" = pick in the UI)
  std::string script;      // --script FILE: commands run one after another (see ParseScript)
  std::string screenshot;  // headless: PNG written at the end (the last frame, with the UI)
  bool headless = false;   // no window: OSMesa/EGL context (implied by --screenshot)
  bool overlay = true;     // draw the ImGui panels into headless frames
  int width = 1280, height = 720;
  int exit_after = 0;          // window: close after this many frames (0 = when the user closes it)
  bool print_widgets = false;  // print "widget NAME x0 y0 x1 y1" for the first frame's widgets
  // While the worker computes, the 3-D scene is rendered again at most this often [ms] (the
  // panels every frame); camera or size changes and screenshots render at once (ScenePacer).
  double preview_interval_ms = 200.0;
  planning::RobotInputOptions robot_input;  // --package-path, --srdf
};

// Runs the viewer; returns the process exit code (0 ok). Throws render::ContextError when no
// window/context can be created (exit 3) and std::invalid_argument for bad files (exit 2).
int RunViewer(const ViewerOptions& options);

}  // namespace app::ui
