// Dear ImGui panels of the viewer. Panels edit Settings in place and push Commands; they never
// call planners or the renderer themselves (docs/architecture.md §2.3).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "app/viewer/session.h"
#include "app/viewer/settings.h"

namespace app::ui {

// Screen rectangles of the named widgets drawn in the last frame ("Plan", "Step sweep", "chains",
// ...), in framebuffer pixels: what `--script` `click NAME` and the xvfb test aim at.
struct WidgetRects {
  struct Rect {
    float x0, y0, x1, y1;
  };
  std::map<std::string, Rect> rects;
};

// Draws every panel for one frame. `scenarios` and `grasps` list the pickers' choices.
void DrawPanels(const Session& session, const std::vector<std::string>& scenarios,
                const std::vector<std::string>& grasps, Settings* settings,
                std::vector<SessionCommand>* commands, WidgetRects* rects);

}  // namespace app::ui
