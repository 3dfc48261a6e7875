// The GL 3.3 core renderer of a render::Scene.
//
// Requires a current GL context (OffscreenContext, or later a GLFW window) and does not create
// one; it loads every GL entry point it uses through the GlProcLoader it is given. It draws:
// shapes (instances of shared unit meshes; spheres and cylinders in 3 levels of detail chosen by
// projected size: 12/20/32 slices below 6 px / 20 px / above), tubes (cylinder per segment +
// bead spheres), GL lines, and a ground grid (procedural, in the fragment shader) with
// Blinn-Phong lighting from up to 4 directional lights plus hemispheric ambient, and a soft
// shadow (shadow map of RenderOptions::shadow_map_size², default 1024², 4-tap bilinear PCF) from
// the first light onto everything. Spheres, cylinders, capsules and boxes are closed and drawn with
// back faces culled (a near plane that cuts into one shows through the cut). Renders are
// deterministic: the same Scene, Camera, size and options give byte-identical pixels run to run
// (tessellation counts are fixed; no time).
//
// Cost on the 2-core reference machine (tests/bench/bench_render.cc): see the README.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/overlay.h"
#include "render/scene.h"

namespace render {

struct RenderOptions {
  int msaa_samples = 0;  // 0 or 1: none; 2/4: multisampled FBO resolved before readback
  bool shadows = true;   // shadow of the first light (off: plain Blinn-Phong)
  // Texels on a side of the shadow map: a power of two in [64, 4096]. Its depth pass costs about
  // size² fragments whatever the frame size, so small frames can take a smaller map (softer,
  // coarser shadow edges); 1024 is what every golden image was rendered with.
  int shadow_map_size = 1024;
};

// GL implementation strings of the current context (for logs and snapshots/README.md).
struct GlInfo {
  std::string version;   // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"
  std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
};

class Renderer {
 public:
  // Loads GL entry points with `load` and compiles the shaders. Requires the context that `load`
  // belongs to to be current, and GL >= 3.3 core; throws ContextError otherwise.
  explicit Renderer(const GlProcLoader& load);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders `scene` seen by `camera` into an internal width x height framebuffer object and reads
  // it back (rows top-down, alpha 255). Throws std::invalid_argument for sizes outside
  // [1, 8192] or a degenerate camera (eye == target, up parallel to the view direction, fovy
  // outside (0, 180)).
  // If `overlay` is not null it is drawn over the scene (same pixels as DrawOverlay in a window).
  Image Render(const Scene& scene, const Camera& camera, int width, int height,
               const RenderOptions& options = {}, const Overlay* overlay = nullptr);

  // Draws into the framebuffer object `fbo` (0: the window's default framebuffer) of size
  // width x height without reading back; for the interactive viewer. Leaves the viewport set.
  void Draw(const Scene& scene, const Camera& camera, int width, int height, unsigned fbo,
            const RenderOptions& options = {});

  // Draws a 2-D overlay (the viewer's ImGui panels) over the framebuffer `fbo` of size
  // width x height, which already holds a frame; no depth test, source-alpha blending.
  void DrawOverlay(const Overlay& overlay, int width, int height, unsigned fbo);

  // Scene cache, for a viewer whose 3-D scene changes far less often than its panels: renders
  // `scene` (as Draw, MSAA resolved) into an internal width x height colour target that keeps
  // the image until the next CacheScene call. Throws as Render.
  void CacheScene(const Scene& scene, const Camera& camera, int width, int height,
                  const RenderOptions& options = {});
  // Copies the cached scene image into framebuffer `fbo` (0: the window's default framebuffer),
  // which must be the cached size; leaves the viewport set. Throws std::logic_error when nothing
  // is cached.
  void DrawCachedScene(unsigned fbo);
  // The cached scene with `overlay` (if not null) drawn over it, read back: byte-identical to
  // Render(scene, camera, width, height, options, overlay) with CacheScene's arguments. Throws
  // std::logic_error when nothing is cached.
  Image ReadCachedScene(const Overlay* overlay);

  GlInfo info() const;

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Column-major 4x4 matrices the renderer uses (OpenGL conventions: camera looks down -z, clip
// space -1..1). Exposed for tests and for picking in the viewer.
Eigen::Matrix4f ViewMatrix(const Camera& camera);
Eigen::Matrix4f ProjectionMatrix(const Camera& camera, float aspect, float near_clip,
                                 float far_clip);

// Pixel position (column u, row v; top-left corner of the image is (0,0), pixel centres at
// +0.5) where the world point `p` projects in a width x height image. Returns false if p is
// behind the camera.
bool ProjectToPixel(const Camera& camera, int width, int height, const Eigen::Vector3f& p,
                    Eigen::Vector2f* pixel);

}  // namespace render
