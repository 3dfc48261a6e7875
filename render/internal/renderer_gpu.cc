// GL resources of the scene renderer (see renderer_impl.h): meshes uploaded as vertex arrays
// with an instance buffer (and the cache of user meshes, keyed by TriangleMesh object), instanced
// draws, the 1024^2 depth-texture shadow map, and the colour+depth framebuffer targets (single-
// or multisampled) that frames are drawn into, resolved and copied between.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "render/internal/renderer_impl.h"
#include "render/internal/tessellate.h"

namespace render {

internal::GpuMesh Renderer::Impl::Upload(const TriangleMesh& input) {
  const TriangleMesh mesh = internal::WithNormals(input);
  GpuMesh g;
  std::vector<float> interleaved;
  interleaved.reserve(6 * mesh.positions.size());
  float r2 = 0.0f;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) interleaved.push_back(mesh.positions[i][c]);
    for (int c = 0; c < 3; ++c) interleaved.push_back(mesh.normals[i][c]);
    r2 = std::max(r2, mesh.positions[i].squaredNorm());
  }
  g.bound_radius = std::sqrt(r2);
  g.index_count = static_cast<GLsizei>(mesh.indices.size());
  gl_.GenVertexArrays(1, &g.vao);
  gl_.GenBuffers(1, &g.vertex_buffer);
  gl_.GenBuffers(1, &g.index_buffer);
  gl_.GenBuffers(1, &g.instance_buffer);
  gl_.BindVertexArray(g.vao);
  gl_.BindBuffer(GL_ARRAY_BUFFER, g.vertex_buffer);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                 interleaved.data(), GL_STATIC_DRAW);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  gl_.EnableVertexAttribArray(1);
  gl_.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<void*>(3 * sizeof(float)));
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.index_buffer);
  gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
  gl_.BindBuffer(GL_ARRAY_BUFFER, g.instance_buffer);
  // Instance attributes: model columns (2..5), colour (6), material (7), normal matrix
  // columns (8..10).
  for (int k = 0; k < 9; ++k) {
    const auto location = static_cast<GLuint>(2 + k);
    gl_.EnableVertexAttribArray(location);
    gl_.VertexAttribPointer(
        location, k < 6 ? 4 : 3, GL_FLOAT, GL_FALSE, sizeof(Instance),
        reinterpret_cast<void*>((k < 6 ? 4 * k : 24 + 3 * (k - 6)) * sizeof(float)));
    gl_.VertexAttribDivisor(location, 1);
  }
  gl_.BindVertexArray(0);
  return g;
}

void Renderer::Impl::Release(GpuMesh* g) {
  gl_.DeleteVertexArrays(1, &g->vao);
  GLuint buffers[] = {g->vertex_buffer, g->index_buffer, g->instance_buffer};
  gl_.DeleteBuffers(3, buffers);
  *g = GpuMesh{};
}

const internal::GpuMesh* Renderer::Impl::MeshFor(const std::shared_ptr<const TriangleMesh>& mesh) {
  auto it = mesh_cache_.find(mesh.get());
  if (it != mesh_cache_.end() && it->second.owner.lock() == mesh) return &it->second.gpu;
  if (it != mesh_cache_.end()) {
    Release(&it->second.gpu);
    mesh_cache_.erase(it);
  }
  // Drop entries whose meshes are gone so the cache does not grow without bound.
  for (auto e = mesh_cache_.begin(); e != mesh_cache_.end();) {
    if (e->second.owner.expired()) {
      Release(&e->second.gpu);
      e = mesh_cache_.erase(e);
    } else {
      ++e;
    }
  }
  CachedMesh entry{mesh, Upload(*mesh)};
  return &mesh_cache_.emplace(mesh.get(), entry).first->second.gpu;
}

void Renderer::Impl::DrawInstances(const GpuMesh& mesh, const std::vector<Instance>& items) {
  if (items.empty()) return;
  gl_.BindVertexArray(mesh.vao);
  gl_.BindBuffer(GL_ARRAY_BUFFER, mesh.instance_buffer);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(items.size() * sizeof(Instance)),
                 items.data(), GL_STREAM_DRAW);
  gl_.DrawElementsInstanced(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(items.size()));
  gl_.BindVertexArray(0);
}

void Renderer::Impl::CreateShadowMap(int size) {
  const bool resize = shadow_texture_ != 0;
  if (!resize) gl_.GenTextures(1, &shadow_texture_);
  gl_.BindTexture(GL_TEXTURE_2D, shadow_texture_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, nullptr);
  shadow_size_ = size;
  if (resize) return;  // new storage; the parameters and the framebuffer's attachment stay
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  gl_.GenFramebuffers(1, &shadow_fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture_, 0);
  gl_.DrawBuffer(GL_NONE);
  gl_.ReadBuffer(GL_NONE);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw ContextError("GL: shadow-map framebuffer incomplete");
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::Impl::MakeTarget(int width, int height, int samples, Target* t) {
  gl_.GenFramebuffers(1, &t->fbo);
  gl_.GenRenderbuffers(1, &t->color);
  gl_.GenRenderbuffers(1, &t->depth);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, t->color);
  if (samples) {
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
  } else {
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  }
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->color);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, t->depth);
  if (samples) {
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width,
                                       height);
  } else {
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
  }
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              t->depth);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    throw ContextError("GL: framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                       " with " + std::to_string(samples) +
                       " samples is incomplete (MSAA unsupported?)");
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::Impl::ReleaseTarget(Target* t) {
  if (t->fbo) gl_.DeleteFramebuffers(1, &t->fbo);
  for (GLuint* r : {&t->color, &t->depth}) {
    if (*r) gl_.DeleteRenderbuffers(1, r);
  }
  *t = Target{};
}

void Renderer::Impl::Copy(GLuint from, GLuint to, int width, int height) {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, from);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
  gl_.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void Renderer::Impl::EnsureTargets(int width, int height, int samples) {
  if (target_.fbo && width == target_w_ && height == target_h_ && samples == target_samples_) {
    return;
  }
  ReleaseTargets();
  MakeTarget(width, height, 0, &target_);
  if (samples) MakeTarget(width, height, samples, &msaa_);
  target_w_ = width;
  target_h_ = height;
  target_samples_ = samples;
}

void Renderer::Impl::ReleaseTargets() {
  ReleaseTarget(&target_);
  ReleaseTarget(&msaa_);
}

}  // namespace render
