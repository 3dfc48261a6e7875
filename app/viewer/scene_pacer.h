// When the viewer renders its 3-D scene again. Rasterising the scene is most of a frame's cost
// on a software GL (llvmpipe), while the panels change every frame; so the scene is rendered into
// a cached image (render::Renderer::CacheScene) only when what it shows changed, and every frame
// draws that image plus the panels. "Changed" is judged by two 64-bit keys per frame: a hash of
// the built render::Scene (everything the renderer reads from it) and one of the camera and frame
// size. While the worker computes (a plan streams sweeps, a simulation streams frames) content
// changes re-render at most every `interval_s` of wall time, so progress text and bars keep every
// frame and the 3-D preview refreshes a few times a second; a camera or size change re-renders at
// once, and a screenshot always does (forced).
#pragma once

#include <cstdint>

#include "render/scene.h"

namespace app::ui {

// 64-bit hash (FNV-1a over 32-bit words) of every field of `scene` the renderer reads: shapes
// (kind, pose, size, material, mesh identity and size), tubes, lines, grid, lights, ambient,
// background. Equal scenes hash equal; O(size of the scene).
std::uint64_t SceneHash(const render::Scene& scene);

// Hash of the camera (eye, target, up, fovy, clip planes) and the frame size in pixels.
std::uint64_t ViewHash(const render::Camera& camera, int width, int height);

class ScenePacer {
 public:
  // interval_s >= 0: the least wall time [s] between two renders caused by content changes
  // while the worker computes (0: every frame).
  explicit ScenePacer(double interval_s = 0.2) : interval_s_(interval_s) {}

  // Whether the frame with these keys must render the scene at wall time now_s [s]: when
  // `force`d, when nothing was rendered yet or the view key changed; when the content key
  // changed and either the worker is idle (`busy` false) or interval_s passed since the last
  // render. False while the cached image shows exactly these keys.
  bool Due(std::uint64_t content, std::uint64_t view, bool busy, bool force, double now_s) const;
  // Records a render of these keys at now_s.
  void Rendered(std::uint64_t content, std::uint64_t view, double now_s);
  // Renders recorded so far.
  long renders() const { return renders_; }
  double interval_s() const { return interval_s_; }

 private:
  double interval_s_;
  bool rendered_ = false;
  std::uint64_t content_ = 0, view_ = 0;
  double last_s_ = 0.0;
  long renders_ = 0;
};

}  // namespace app::ui
