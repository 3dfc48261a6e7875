// The GL 3.3 core scene renderer (see renderer.h): the camera matrices, set-up and tear-down of
// the GL state (Renderer::Impl, declared in internal/renderer_impl.h), the read-back, cache and
// overlay entry points, and the public Renderer forwarding to Impl.
//
// Per frame (internal/renderer_passes.cc): 1. turn every shape, tube segment and bead into
// instances of four shared unit meshes (or of a cached user mesh; internal/renderer_collect.cc);
// 2. compute the scene's bounding sphere for clip planes and the shadow frustum; 3. depth pass
// from light 0 into a shadow map (RenderOptions::shadow_map_size, default 1024^2); 4. lit pass:
// opaque instance batches, grid, translucent instances back to front, lines; 5. (Render only)
// resolve MSAA and read back, flipping rows to top-down.
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/str_cat.h"
#include "render/internal/renderer_impl.h"
#include "render/internal/shaders.h"
#include "render/internal/tessellate.h"

namespace render {
namespace {

constexpr int kMaxSize = 8192;

}  // namespace

Eigen::Matrix4f ViewMatrix(const Camera& camera) {
  const Eigen::Vector3f f = (camera.target - camera.eye).normalized();
  const Eigen::Vector3f s = f.cross(camera.up).normalized();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(camera.eye);
  m(1, 3) = -u.dot(camera.eye);
  m(2, 3) = f.dot(camera.eye);
  return m;
}

Eigen::Matrix4f ProjectionMatrix(const Camera& camera, float aspect, float near_clip,
                                 float far_clip) {
  const float t = 1.0f / std::tan(0.5f * camera.fovy_deg * 3.14159265358979f / 180.0f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = -(far_clip + near_clip) / (far_clip - near_clip);
  m(2, 3) = -2.0f * far_clip * near_clip / (far_clip - near_clip);
  m(3, 2) = -1.0f;
  return m;
}

bool ProjectToPixel(const Camera& camera, int width, int height, const Eigen::Vector3f& p,
                    Eigen::Vector2f* pixel) {
  const Eigen::Vector4f c = ViewMatrix(camera) * p.homogeneous();
  if (c.z() >= 0.0f) return false;
  const float f = 0.5f * static_cast<float>(height) /
                  std::tan(0.5f * camera.fovy_deg * 3.14159265358979f / 180.0f);
  *pixel = Eigen::Vector2f(0.5f * static_cast<float>(width) + f * c.x() / -c.z(),
                           0.5f * static_cast<float>(height) - f * c.y() / -c.z());
  return true;
}

Renderer::Impl::Impl(const GlProcLoader& load) {
  internal::LoadGlApi(load, &gl_);
  const char* version = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
  GLint major = 0, minor = 0;
  gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
  if (version == nullptr || major * 10 + minor < 33) {
    throw ContextError(std::string("GL: need OpenGL >= 3.3 core, context reports '") +
                       (version ? version : "(none)") + "'");
  }
  const std::string grid_fs =
      base::StrCat(internal::kShadowLookupShader, internal::kGridFragmentShader);
  for (int shadows = 0; shadows < 2; ++shadows) {
    const std::string prefix =
        base::StrCat("#version 330 core\n#define SHADOWS ", std::to_string(shadows), "\n");
    grid_programs_[shadows] = internal::LinkProgram(gl_, internal::kMeshVertexShader,
                                                    grid_fs.c_str(), "grid", prefix.c_str());
    MeshProgram(shadows != 0, 2);  // the default light rig's; others on first use
  }
  depth_program_ = internal::LinkProgram(gl_, internal::kDepthVertexShader,
                                         internal::kDepthFragmentShader, "depth");
  line_program_ = internal::LinkProgram(gl_, internal::kLineVertexShader,
                                        internal::kLineFragmentShader, "line");
  for (int lod = 0; lod < 3; ++lod) {
    sphere_[lod] = Upload(internal::UnitSphere(internal::kLodSlices[lod]));
    cylinder_[lod] = Upload(internal::UnitCylinder(internal::kLodSlices[lod]));
  }
  box_ = Upload(internal::UnitBox());
  for (GpuMesh* closed : {&sphere_[0], &sphere_[1], &sphere_[2], &cylinder_[0], &cylinder_[1],
                          &cylinder_[2], &box_}) {
    closed->closed = true;
  }
  quad_ = Upload(internal::UnitQuad());
  gl_.GenVertexArrays(1, &line_vao_);
  gl_.GenBuffers(1, &line_buffer_);
  gl_.BindVertexArray(line_vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, line_buffer_);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  gl_.BindVertexArray(0);
  CreateShadowMap(RenderOptions{}.shadow_map_size);
}

Renderer::Impl::~Impl() {
  for (int lod = 0; lod < 3; ++lod) {
    Release(&sphere_[lod]);
    Release(&cylinder_[lod]);
  }
  Release(&box_);
  Release(&quad_);
  for (auto& [key, entry] : mesh_cache_) Release(&entry.gpu);
  gl_.DeleteVertexArrays(1, &line_vao_);
  gl_.DeleteBuffers(1, &line_buffer_);
  for (int shadows = 0; shadows < 2; ++shadows) {
    for (GLuint program : mesh_programs_[shadows]) {
      if (program) gl_.DeleteProgram(program);
    }
    gl_.DeleteProgram(grid_programs_[shadows]);
  }
  gl_.DeleteProgram(depth_program_);
  gl_.DeleteProgram(line_program_);
  gl_.DeleteFramebuffers(1, &shadow_fbo_);
  gl_.DeleteTextures(1, &shadow_texture_);
  ReleaseTargets();
  ReleaseTarget(&cache_);
}

GlInfo Renderer::Impl::info() const {
  GlInfo i;
  const auto* v = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
  const auto* r = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
  i.version = v ? v : "";
  i.renderer = r ? r : "";
  return i;
}

void Renderer::Impl::CheckSize(int width, int height) {
  if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize) {
    throw std::invalid_argument("render size " + std::to_string(width) + "x" +
                                std::to_string(height) + " outside 1..8192");
  }
}

Image Renderer::Impl::Render(const Scene& scene, const Camera& camera, int width, int height,
                             const RenderOptions& options, const Overlay* overlay) {
  CheckSize(width, height);
  const int samples = options.msaa_samples > 1 ? options.msaa_samples : 0;
  EnsureTargets(width, height, samples);
  Draw(scene, camera, width, height, samples ? msaa_.fbo : target_.fbo, options);
  if (samples) Copy(msaa_.fbo, target_.fbo, width, height);
  if (overlay != nullptr) DrawOverlay(*overlay, width, height, target_.fbo);
  return ReadBack(width, height);
}

void Renderer::Impl::CacheScene(const Scene& scene, const Camera& camera, int width, int height,
                                const RenderOptions& options) {
  CheckSize(width, height);
  const int samples = options.msaa_samples > 1 ? options.msaa_samples : 0;
  if (!cache_.fbo || width != cache_w_ || height != cache_h_) {
    ReleaseTarget(&cache_);
    cache_w_ = cache_h_ = 0;
    MakeTarget(width, height, 0, &cache_);
    cache_w_ = width;
    cache_h_ = height;
  }
  if (samples) {
    EnsureTargets(width, height, samples);
    Draw(scene, camera, width, height, msaa_.fbo, options);
    Copy(msaa_.fbo, cache_.fbo, width, height);
  } else {
    Draw(scene, camera, width, height, cache_.fbo, options);
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::Impl::DrawCachedScene(GLuint fbo) {
  if (!cache_.fbo) throw std::logic_error("DrawCachedScene: no scene cached");
  Copy(cache_.fbo, fbo, cache_w_, cache_h_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl_.Viewport(0, 0, cache_w_, cache_h_);
}

Image Renderer::Impl::ReadCachedScene(const Overlay* overlay) {
  if (!cache_.fbo) throw std::logic_error("ReadCachedScene: no scene cached");
  if (!target_.fbo || target_w_ != cache_w_ || target_h_ != cache_h_) {
    EnsureTargets(cache_w_, cache_h_, 0);
  }
  Copy(cache_.fbo, target_.fbo, cache_w_, cache_h_);
  if (overlay != nullptr) DrawOverlay(*overlay, cache_w_, cache_h_, target_.fbo);
  return ReadBack(cache_w_, cache_h_);
}

Image Renderer::Impl::ReadBack(int width, int height) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, target_.fbo);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  Image out;
  out.width = width;
  out.height = height;
  out.rgba.resize(4 * static_cast<size_t>(width) * height);
  gl_.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  // GL rows are bottom-up: swap them in place. Alpha is already 255 everywhere (cleared to 1,
  // and blending keeps destination alpha 1).
  const size_t row = 4 * static_cast<size_t>(width);
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(out.rgba.begin() + static_cast<std::ptrdiff_t>(row * y),
                     out.rgba.begin() + static_cast<std::ptrdiff_t>(row * (y + 1)),
                     out.rgba.begin() + static_cast<std::ptrdiff_t>(row * (height - 1 - y)));
  }
  return out;
}

void Renderer::Impl::DrawOverlay(const Overlay& overlay, int width, int height, GLuint fbo) {
  CheckSize(width, height);
  if (!overlay_pass_) overlay_pass_ = std::make_unique<internal::OverlayPass>(gl_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl_.Viewport(0, 0, width, height);
  overlay_pass_->Draw(overlay, width, height);
}

Renderer::Renderer(const GlProcLoader& load) : impl_(std::make_unique<Impl>(load)) {}
Renderer::~Renderer() = default;

Image Renderer::Render(const Scene& scene, const Camera& camera, int width, int height,
                       const RenderOptions& options, const Overlay* overlay) {
  return impl_->Render(scene, camera, width, height, options, overlay);
}

void Renderer::DrawOverlay(const Overlay& overlay, int width, int height, unsigned fbo) {
  impl_->DrawOverlay(overlay, width, height, fbo);
}

void Renderer::Draw(const Scene& scene, const Camera& camera, int width, int height, unsigned fbo,
                    const RenderOptions& options) {
  impl_->Draw(scene, camera, width, height, fbo, options);
}

void Renderer::CacheScene(const Scene& scene, const Camera& camera, int width, int height,
                          const RenderOptions& options) {
  impl_->CacheScene(scene, camera, width, height, options);
}

void Renderer::DrawCachedScene(unsigned fbo) { impl_->DrawCachedScene(fbo); }

Image Renderer::ReadCachedScene(const Overlay* overlay) { return impl_->ReadCachedScene(overlay); }

GlInfo Renderer::info() const { return impl_->info(); }

}  // namespace render
