// GL pass that draws a render::Overlay into the currently bound framebuffer.
#pragma once

#include <cstdint>
#include <vector>

#include "render/internal/gl_api.h"
#include "render/overlay.h"

namespace render::internal {

class OverlayPass {
 public:
  // Compiles the overlay program and creates its buffers; requires the context of `gl` current.
  // `gl` must outlive the pass.
  explicit OverlayPass(const GlApi& gl);
  ~OverlayPass();
  OverlayPass(const OverlayPass&) = delete;
  OverlayPass& operator=(const OverlayPass&) = delete;

  // Draws `overlay` over a width x height framebuffer that is bound with its viewport set.
  // Leaves blending, scissor and depth state as it found them (depth test on, blend/scissor off).
  void Draw(const Overlay& overlay, int width, int height);

 private:
  void UploadTexture(const Overlay& overlay);

  const GlApi& gl_;
  GLuint program_ = 0, vao_ = 0, vbo_ = 0, ebo_ = 0, texture_ = 0, white_ = 0;
  GLint viewport_location_ = -1, sampler_location_ = -1;
  const Image* texture_source_ = nullptr;
  std::uint64_t texture_revision_ = 0;
  int texture_width_ = 0, texture_height_ = 0;
  std::vector<std::uint32_t> absolute_indices_;  // indices with vertex_offset applied
};

}  // namespace render::internal
