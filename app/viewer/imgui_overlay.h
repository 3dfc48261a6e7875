// Dear ImGui → render::Overlay: the only bridge between ImGui's draw lists and the renderer, so
// that the offscreen frames (--overlay, snapshots) and the window draw the UI the same way.
#pragma once

#include <imgui.h>

#include "render/image.h"
#include "render/overlay.h"

namespace app::ui {

// Builds the current ImGui context's font atlas as RGBA (white glyphs, coverage in alpha) into
// `atlas` and registers it as the atlas texture. Call once after the fonts are configured.
void BuildFontAtlas(render::Image* atlas);

// Copies the draw lists of `draw_data` (after ImGui::Render()) into `overlay`, in framebuffer
// pixels, with clip rectangles; `atlas` becomes the overlay's texture. Reuses `overlay`'s storage.
void ToOverlay(const ImDrawData& draw_data, const render::Image* atlas, render::Overlay* overlay);

}  // namespace app::ui
