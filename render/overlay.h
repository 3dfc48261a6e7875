// render::Overlay: 2-D user-interface geometry drawn over a 3-D frame, in pixels.
//
// This is the renderer's own vocabulary for what Dear ImGui produces (app/ui converts ImDrawData
// into it), so render/ knows nothing of ImGui and the same overlay can be drawn into an offscreen
// frame (`--overlay`, snapshot tests) or into the interactive window.
#pragma once

#include <cstdint>
#include <vector>

#include "render/image.h"

namespace render {

// One vertex in pixel coordinates (origin top-left, x right, y down), texture coordinates into the
// overlay's texture, and a colour packed as 0xAABBGGRR (R in the low byte, straight alpha).
struct OverlayVertex {
  float x = 0, y = 0;
  float u = 0, v = 0;
  std::uint32_t abgr = 0xffffffffu;
};

// A run of `index_count` indices starting at `index_offset`, added to `vertex_offset`, drawn with
// the pixel clip rectangle [clip_min_x, clip_max_x) × [clip_min_y, clip_max_y).
struct OverlayCommand {
  std::uint32_t index_offset = 0;
  std::uint32_t index_count = 0;
  std::uint32_t vertex_offset = 0;
  float clip_min_x = 0, clip_min_y = 0, clip_max_x = 0, clip_max_y = 0;
};

// Triangles (3 indices each) blended over the frame with premultiplied-free "source alpha"
// blending, no depth test. `texture` is sampled with the vertices' u, v and multiplied by their
// colour; it must stay alive while the overlay is drawn. The renderer uploads it again only when
// `texture_revision` changes (or the pointer or size does).
struct Overlay {
  std::vector<OverlayVertex> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<OverlayCommand> commands;
  const Image* texture = nullptr;
  std::uint64_t texture_revision = 0;
};

}  // namespace render
