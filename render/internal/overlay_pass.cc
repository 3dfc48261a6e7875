#include "render/internal/overlay_pass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/internal/shaders.h"

namespace render::internal {

OverlayPass::OverlayPass(const GlApi& gl) : gl_(gl) {
  program_ = LinkProgram(gl_, kOverlayVertexShader, kOverlayFragmentShader, "overlay");
  viewport_location_ = gl_.GetUniformLocation(program_, "viewport");
  sampler_location_ = gl_.GetUniformLocation(program_, "atlas");

  gl_.GenVertexArrays(1, &vao_);
  gl_.GenBuffers(1, &vbo_);
  gl_.GenBuffers(1, &ebo_);
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  const GLsizei stride = sizeof(OverlayVertex);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(offsetof(OverlayVertex, x)));
  gl_.EnableVertexAttribArray(1);
  gl_.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(offsetof(OverlayVertex, u)));
  gl_.EnableVertexAttribArray(2);
  gl_.VertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride,
                          reinterpret_cast<void*>(offsetof(OverlayVertex, abgr)));
  gl_.BindVertexArray(0);

  // A 1x1 white texture for overlays without one.
  const std::uint8_t white[4] = {255, 255, 255, 255};
  gl_.GenTextures(1, &white_);
  gl_.BindTexture(GL_TEXTURE_2D, white_);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
  gl_.GenTextures(1, &texture_);
}

OverlayPass::~OverlayPass() {
  gl_.DeleteTextures(1, &texture_);
  gl_.DeleteTextures(1, &white_);
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteBuffers(1, &ebo_);
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteProgram(program_);
}

void OverlayPass::UploadTexture(const Overlay& overlay) {
  const Image* t = overlay.texture;
  if (t == texture_source_ && overlay.texture_revision == texture_revision_ &&
      t->width == texture_width_ && t->height == texture_height_) {
    return;
  }
  gl_.BindTexture(GL_TEXTURE_2D, texture_);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t->width, t->height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 t->rgba.data());
  texture_source_ = t;
  texture_revision_ = overlay.texture_revision;
  texture_width_ = t->width;
  texture_height_ = t->height;
}

void OverlayPass::Draw(const Overlay& overlay, int width, int height) {
  if (overlay.commands.empty() || width <= 0 || height <= 0) return;
  const bool textured = overlay.texture != nullptr && !overlay.texture->empty();
  if (textured) UploadTexture(overlay);

  // Indices become absolute so that one buffer serves every command (GL 3.3 has no base vertex
  // in the entry points the renderer loads).
  absolute_indices_.resize(overlay.indices.size());
  for (const OverlayCommand& c : overlay.commands) {
    const std::uint32_t end = std::min<std::uint32_t>(
        c.index_offset + c.index_count, static_cast<std::uint32_t>(overlay.indices.size()));
    for (std::uint32_t i = c.index_offset; i < end; ++i) {
      absolute_indices_[i] = overlay.indices[i] + c.vertex_offset;
    }
  }

  gl_.UseProgram(program_);
  gl_.Uniform2f(viewport_location_, static_cast<float>(width), static_cast<float>(height));
  gl_.Uniform1i(sampler_location_, 0);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, textured ? texture_ : white_);
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(overlay.vertices.size() * sizeof(OverlayVertex)),
                 overlay.vertices.data(), GL_STREAM_DRAW);
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(absolute_indices_.size() * sizeof(std::uint32_t)),
                 absolute_indices_.data(), GL_STREAM_DRAW);

  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_CULL_FACE);
  gl_.Enable(GL_BLEND);
  gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl_.Enable(GL_SCISSOR_TEST);
  for (const OverlayCommand& c : overlay.commands) {
    if (c.index_count == 0) continue;
    // Clip rectangle in GL's bottom-left pixel coordinates, clamped to the framebuffer.
    const int x0 = std::clamp(static_cast<int>(std::floor(c.clip_min_x)), 0, width);
    const int y0 = std::clamp(static_cast<int>(std::floor(c.clip_min_y)), 0, height);
    const int x1 = std::clamp(static_cast<int>(std::ceil(c.clip_max_x)), 0, width);
    const int y1 = std::clamp(static_cast<int>(std::ceil(c.clip_max_y)), 0, height);
    if (x1 <= x0 || y1 <= y0) continue;
    gl_.Scissor(x0, height - y1, x1 - x0, y1 - y0);
    gl_.DrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(c.index_count), GL_UNSIGNED_INT,
                              reinterpret_cast<void*>(static_cast<std::uintptr_t>(c.index_offset) *
                                                      sizeof(std::uint32_t)),
                              1);
  }
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.Disable(GL_BLEND);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
}

}  // namespace render::internal
