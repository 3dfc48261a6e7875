// One frame of the scene renderer (Renderer::Impl::Draw, see renderer_impl.h): collect the
// scene's instances, fit clip planes and the shadow frustum to their bounds, render the shadow
// map from light 0 (opaque batches), then the lit pass (opaque batches, the ground grid behind
// them, translucent instances back to front, lines) into the target framebuffer. Closed unit
// meshes are drawn with back faces culled in the lit pass, and the grid looks up the shadow map
// only inside the screen rectangle that light 0 can shadow (frame_geometry.h: GroundShadowRect).
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/str_cat.h"
#include "render/internal/frame_geometry.h"
#include "render/internal/renderer_impl.h"
#include "render/internal/shaders.h"

namespace render {

using internal::Bounds;
using internal::LitFrame;

void Renderer::Impl::Draw(const Scene& scene, const Camera& camera, int width, int height,
                          GLuint fbo, const RenderOptions& options) {
  CheckSize(width, height);
  internal::CheckCamera(camera);
  const int sm = options.shadow_map_size;
  if (sm < 64 || sm > 4096 || (sm & (sm - 1)) != 0) {
    throw std::invalid_argument("shadow_map_size " + std::to_string(sm) +
                                " is not a power of two in 64..4096");
  }
  focal_px_ = 0.5f * static_cast<float>(height) /
              std::tan(0.5f * camera.fovy_deg * 3.14159265358979f / 180.0f);
  lod_eye_ = camera.eye;
  lod_forward_ = (camera.target - camera.eye).normalized();
  Collect(scene);

  // Bounds -> clip planes and the shadow frustum.
  const Bounds casters = OpaqueBounds();
  const Bounds bounds = FrameBounds(casters, scene.lines);
  const internal::BoundingSphere sphere = internal::SphereAround(bounds);
  const internal::ClipRange clip =
      internal::FrameClipRange(camera, internal::WithGrid(bounds, scene.grid));
  LitFrame frame;
  frame.view_proj = ProjectionMatrix(camera, static_cast<float>(width) / static_cast<float>(height),
                                     clip.near_clip, clip.far_clip) *
                    ViewMatrix(camera);

  // Lights: the scene's, or a default rig attached to the camera.
  const std::vector<Light> lights = internal::FrameLights(scene, camera);

  // Shadow pass.
  frame.shadows = options.shadows && !bounds.empty() && lights[0].direction.norm() > 0.0f;
  frame.light_view_proj = Eigen::Matrix4f::Identity();
  frame.shadow_map_size = options.shadow_map_size;
  if (frame.shadows) {
    frame.light_view_proj = internal::LightViewProjection(sphere, lights[0].direction);
    ShadowPass(frame.light_view_proj, frame.shadow_map_size);
    // Filter reach of a lookup (2 taps 0.75 texel off centre, bilinear, raster rounding):
    // under 4 texels of 2 radius / shadow_map_size; 5 for margin.
    const float reach = 5.0f * 2.0f * sphere.radius / static_cast<float>(frame.shadow_map_size);
    frame.ground_shadow_rect = internal::GroundShadowRect(
        casters, reach, lights[0].direction, scene.grid.height, frame.view_proj, width, height);
  }

  frame.num_lights = static_cast<int>(lights.size());
  for (size_t k = 0; k < lights.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      frame.light_dir[3 * k + c] = lights[k].direction[c];
      frame.light_rgb[3 * k + c] = lights[k].rgb[c];
    }
  }
  frame.eye = camera.eye;
  frame.up = camera.up.normalized();
  frame.ambient = scene.ambient;
  LitPass(scene, camera, width, height, fbo, frame);
}

GLint Renderer::Impl::Uniform(GLuint program, const char* name) const {
  return gl_.GetUniformLocation(program, name);
}

Bounds Renderer::Impl::OpaqueBounds() const {
  Bounds bounds;
  for (const Batch& batch : opaque_) {
    for (const Instance& inst : batch.items) {
      internal::AddInstanceBounds(&bounds, inst, batch.mesh->bound_radius);
    }
  }
  return bounds;
}

Bounds Renderer::Impl::FrameBounds(const Bounds& opaque, const std::vector<Lines>& lines) const {
  Bounds bounds = opaque;
  for (const auto& [mesh, inst] : translucent_) {
    internal::AddInstanceBounds(&bounds, inst, mesh->bound_radius);
  }
  for (const Lines& l : lines) {
    for (const auto& p : l.points) bounds.Add(p, 0.0f);
  }
  return bounds;
}

void Renderer::Impl::ShadowPass(const Eigen::Matrix4f& light_view_proj, int size) {
  if (size != shadow_size_) CreateShadowMap(size);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  gl_.Viewport(0, 0, size, size);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthMask(GL_TRUE);
  gl_.Clear(GL_DEPTH_BUFFER_BIT);
  gl_.Enable(GL_POLYGON_OFFSET_FILL);
  gl_.PolygonOffset(1.5f, 4.0f);
  gl_.UseProgram(depth_program_);
  gl_.UniformMatrix4fv(gl_.GetUniformLocation(depth_program_, "u_light_view_proj"), 1, GL_FALSE,
                       light_view_proj.data());
  // Unculled: near a caster's outline the slope-scaled offset pushes its front faces back
  // further than the back faces behind them, and without those the light leaks under the edge
  // where a shape rests on the ground.
  DrawOpaque(false);
  gl_.Disable(GL_POLYGON_OFFSET_FILL);
}

void Renderer::Impl::DrawOpaque(bool cull_back_faces) {
  // Culling halves the triangles llvmpipe sets up and rasterises; what is drawn is the same
  // (front faces hide the back faces of a closed surface) up to a pixel on an outline, unless the
  // near plane cuts into the surface.
  for (const Batch& batch : opaque_) {
    const bool cull = cull_back_faces && batch.cull;
    if (cull) gl_.Enable(GL_CULL_FACE);
    DrawInstances(*batch.mesh, batch.items);
    if (cull) gl_.Disable(GL_CULL_FACE);
  }
}

void Renderer::Impl::LitPass(const Scene& scene, const Camera& camera, int width, int height,
                             GLuint fbo, const LitFrame& frame) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl_.Viewport(0, 0, width, height);
  gl_.ClearColor(scene.background[0], scene.background[1], scene.background[2], 1.0f);
  gl_.ClearDepth(1.0);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
  gl_.DepthMask(GL_TRUE);
  gl_.Disable(GL_BLEND);
  gl_.Disable(GL_CULL_FACE);
  gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, shadow_texture_);
  UseLitProgram(frame);
  DrawOpaque(true);
  // The grid after the opaque shapes: the depth test then skips its fragments behind them.
  if (scene.grid.enabled && scene.grid.extent > 0.0f && scene.grid.spacing > 0.0f) {
    DrawGrid(scene.grid, frame, width, height);
  }
  if (!translucent_.empty()) {
    UseLitProgram(frame);
    DrawTranslucent(camera);
  }
  if (!scene.lines.empty()) DrawLines(scene.lines, frame.view_proj);
  gl_.UseProgram(0);
}

GLuint Renderer::Impl::MeshProgram(bool shadows, int num_lights) {
  const int lights = std::clamp(num_lights, 1, 4);
  GLuint& program = mesh_programs_[shadows ? 1 : 0][lights - 1];
  if (!program) {
    const std::string prefix =
        base::StrCat("#version 330 core\n#define SHADOWS ", shadows ? "1" : "0",
                     "\n#define NUM_LIGHTS ", std::to_string(lights), "\n");
    const std::string fragment =
        base::StrCat(internal::kShadowLookupShader, internal::kMeshFragmentShader);
    program = internal::LinkProgram(gl_, internal::kMeshVertexShader, fragment.c_str(), "mesh",
                                    prefix.c_str());
  }
  return program;
}

void Renderer::Impl::UseLitProgram(const LitFrame& frame) {
  const GLuint p = MeshProgram(frame.shadows, frame.num_lights);
  gl_.UseProgram(p);
  gl_.UniformMatrix4fv(Uniform(p, "u_view_proj"), 1, GL_FALSE, frame.view_proj.data());
  gl_.UniformMatrix4fv(Uniform(p, "u_light_view_proj"), 1, GL_FALSE, frame.light_view_proj.data());
  gl_.Uniform3f(Uniform(p, "u_eye"), frame.eye.x(), frame.eye.y(), frame.eye.z());
  gl_.Uniform3f(Uniform(p, "u_up"), frame.up.x(), frame.up.y(), frame.up.z());
  gl_.Uniform3fv(Uniform(p, "u_light_dir"), 4, frame.light_dir.data());
  gl_.Uniform3fv(Uniform(p, "u_light_rgb"), 4, frame.light_rgb.data());
  gl_.Uniform3f(Uniform(p, "u_ambient"), frame.ambient[0], frame.ambient[1], frame.ambient[2]);
  gl_.Uniform1i(Uniform(p, "u_shadow_map"), 0);
  gl_.Uniform1f(Uniform(p, "u_shadow_texel"), 1.0f / static_cast<float>(frame.shadow_map_size));
}

void Renderer::Impl::UseGridProgram(const Grid& g, const LitFrame& frame, bool shadows) {
  const GLuint p = grid_programs_[shadows ? 1 : 0];
  gl_.UseProgram(p);
  gl_.UniformMatrix4fv(Uniform(p, "u_view_proj"), 1, GL_FALSE, frame.view_proj.data());
  gl_.UniformMatrix4fv(Uniform(p, "u_light_view_proj"), 1, GL_FALSE, frame.light_view_proj.data());
  gl_.Uniform4f(Uniform(p, "u_plane_rgba"), g.plane_rgba[0], g.plane_rgba[1], g.plane_rgba[2],
                g.plane_rgba[3]);
  gl_.Uniform2f(Uniform(p, "u_grid_center"), g.center.x(), g.center.y());
  gl_.Uniform1f(Uniform(p, "u_grid_spacing"), g.spacing);
  gl_.Uniform4f(Uniform(p, "u_grid_line"), g.line_rgba[0], g.line_rgba[1], g.line_rgba[2],
                g.line_rgba[3]);
  gl_.Uniform1i(Uniform(p, "u_shadow_map"), 0);
  gl_.Uniform1f(Uniform(p, "u_shadow_texel"), 1.0f / static_cast<float>(frame.shadow_map_size));
  // The mesh shader's lighting for normal n = +z (seen from above) or -z, no highlight
  // (specular 0): ambient mix(0.6, 1, hemi) + sum of rgb max(n.l, 0).
  std::array<float, 6> unshadowed{}, key{};
  std::array<float, 2> key_ndl{};
  for (int side = 0; side < 2; ++side) {
    const float nz = side == 0 ? 1.0f : -1.0f;
    const float hemi = 0.5f + 0.5f * nz * frame.up.z();
    for (int c = 0; c < 3; ++c) {
      unshadowed[3 * side + c] = frame.ambient[c] * (0.6f + 0.4f * hemi);
    }
    for (int k = 0; k < frame.num_lights; ++k) {
      const float ndl = nz * frame.light_dir[3 * k + 2];
      if (k == 0) key_ndl[side] = ndl;
      if (ndl <= 0.0f) continue;
      for (int c = 0; c < 3; ++c) {
        (k == 0 ? key : unshadowed)[3 * side + c] += frame.light_rgb[3 * k + c] * ndl;
      }
    }
  }
  gl_.Uniform3fv(Uniform(p, "u_unshadowed"), 2, unshadowed.data());
  gl_.Uniform3fv(Uniform(p, "u_key"), 2, key.data());
  gl_.Uniform1fv(Uniform(p, "u_key_ndl"), 2, key_ndl.data());
}

void Renderer::Impl::DrawGrid(const Grid& g, const LitFrame& frame, int width, int height) {
  Material flat;
  flat.specular = 0.0f;
  const Eigen::Matrix4f model =
      internal::Translate(Eigen::Vector3f(g.center.x(), g.center.y(), g.height)) *
      internal::Scale(Eigen::Vector3f(g.extent, g.extent, 1.0f));
  scratch_.assign(1, internal::MakeInstance(model, g.plane_rgba, flat));
  // Pushed back in depth so that shapes resting on the ground do not z-fight with it.
  gl_.Enable(GL_POLYGON_OFFSET_FILL);
  gl_.PolygonOffset(1.0f, 2.0f);
  // Shadow lookups cost most of the grid's fragments, and outside the rectangle they all give 1
  // (unshadowed): there the plain variant draws the same pixels. Up to five scissored draws.
  const internal::PixelRect all{0, 0, width, height};
  const internal::PixelRect in = frame.shadows ? frame.ground_shadow_rect : internal::PixelRect{};
  gl_.Enable(GL_SCISSOR_TEST);
  if (!in.empty()) {
    UseGridProgram(g, frame, true);
    gl_.Scissor(in.x0, in.y0, in.x1 - in.x0, in.y1 - in.y0);
    DrawInstances(quad_, scratch_);
  }
  if (!(in == all)) {
    UseGridProgram(g, frame, false);
    const internal::PixelRect around[4] = {
        in.empty() ? all : internal::PixelRect{0, 0, width, in.y0},  // below
        {0, in.y1, width, height},                                   // above
        {0, in.y0, in.x0, in.y1},                                    // left
        {in.x1, in.y0, width, in.y1}};                               // right
    for (int k = 0; k < (in.empty() ? 1 : 4); ++k) {
      const internal::PixelRect& r = around[k];
      if (r.empty()) continue;
      gl_.Scissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
      DrawInstances(quad_, scratch_);
    }
  }
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.Disable(GL_POLYGON_OFFSET_FILL);
}

void Renderer::Impl::DrawTranslucent(const Camera& camera) {
  // Back to front by view depth of the instance origin.
  const Eigen::Matrix4f view = ViewMatrix(camera);
  std::stable_sort(translucent_.begin(), translucent_.end(), [&view](const auto& a, const auto& b) {
    const float za =
        (view * Eigen::Vector4f(a.second.model[12], a.second.model[13], a.second.model[14], 1.0f))
            .z();
    const float zb =
        (view * Eigen::Vector4f(b.second.model[12], b.second.model[13], b.second.model[14], 1.0f))
            .z();
    return za < zb;
  });
  gl_.Enable(GL_BLEND);
  gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl_.DepthMask(GL_FALSE);
  for (const auto& [mesh, inst] : translucent_) {
    scratch_.assign(1, inst);
    DrawInstances(*mesh, scratch_);
  }
  gl_.DepthMask(GL_TRUE);
  gl_.Disable(GL_BLEND);
}

void Renderer::Impl::DrawLines(const std::vector<Lines>& lines, const Eigen::Matrix4f& view_proj) {
  gl_.UseProgram(line_program_);
  gl_.UniformMatrix4fv(Uniform(line_program_, "u_view_proj"), 1, GL_FALSE, view_proj.data());
  gl_.BindVertexArray(line_vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, line_buffer_);
  for (const Lines& l : lines) {
    if (l.points.size() < 2) continue;
    gl_.Uniform4f(Uniform(line_program_, "u_color"), l.rgba[0], l.rgba[1], l.rgba[2], l.rgba[3]);
    gl_.BufferData(GL_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(l.points.size() * sizeof(Eigen::Vector3f)),
                   l.points.data(), GL_STREAM_DRAW);
    gl_.LineWidth(std::max(1.0f, l.width));
    gl_.DrawArrays(l.strip ? GL_LINE_STRIP : GL_LINES, 0,
                   static_cast<GLsizei>(l.strip ? l.points.size() : l.points.size() / 2 * 2));
  }
  gl_.LineWidth(1.0f);
  gl_.BindVertexArray(0);
}

}  // namespace render
