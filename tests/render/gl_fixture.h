// One offscreen context + renderer per test process (OSMesa, or $TOPOPLAN_GL). The context is
// made current on every access because a test may have switched to another context.
#pragma once

#include "render/offscreen_context.h"
#include "render/renderer.h"

namespace render::testing {

inline Renderer& SharedRenderer() {
  static OffscreenContext context;
  static Renderer renderer(context.proc_loader());
  context.MakeCurrent();
  return renderer;
}

}  // namespace render::testing
