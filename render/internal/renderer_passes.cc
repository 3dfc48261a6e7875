// One frame of the scene renderer (Renderer::Impl::Draw, see renderer_impl.h): collect the
// scene's instances, fit clip planes and the shadow frustum to their bounds, render the shadow
// map from light 0, then the lit pass (ground grid, opaque batches, translucent instances back to
// front, lines) into the target framebuffer.
#include <algorithm>
#include <cmath>
#include <vector>

#include "render/internal/frame_geometry.h"
#include "render/internal/renderer_impl.h"

namespace render {

using internal::Bounds;
using internal::LitFrame;

void Renderer::Impl::Draw(const Scene& scene, const Camera& camera, int width, int height,
                          GLuint fbo, const RenderOptions& options) {
  CheckSize(width, height);
  internal::CheckCamera(camera);
  focal_px_ = 0.5f * static_cast<float>(height) /
              std::tan(0.5f * camera.fovy_deg * 3.14159265358979f / 180.0f);
  lod_eye_ = camera.eye;
  lod_forward_ = (camera.target - camera.eye).normalized();
  Collect(scene);

  // Bounds -> clip planes and the shadow frustum.
  const Bounds bounds = FrameBounds(scene.lines);
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
  if (frame.shadows) {
    frame.light_view_proj = internal::LightViewProjection(sphere, lights[0].direction);
    ShadowPass(frame.light_view_proj);
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

Bounds Renderer::Impl::FrameBounds(const std::vector<Lines>& lines) const {
  Bounds bounds;
  for (const auto& batch : opaque_) {
    for (const Instance& inst : batch.second) {
      internal::AddInstanceBounds(&bounds, inst, batch.first->bound_radius);
    }
  }
  for (const auto& [mesh, inst] : translucent_) {
    internal::AddInstanceBounds(&bounds, inst, mesh->bound_radius);
  }
  for (const Lines& l : lines) {
    for (const auto& p : l.points) bounds.Add(p, 0.0f);
  }
  return bounds;
}

void Renderer::Impl::ShadowPass(const Eigen::Matrix4f& light_view_proj) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  gl_.Viewport(0, 0, internal::kShadowMapSize, internal::kShadowMapSize);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthMask(GL_TRUE);
  gl_.Clear(GL_DEPTH_BUFFER_BIT);
  gl_.Enable(GL_POLYGON_OFFSET_FILL);
  gl_.PolygonOffset(1.5f, 4.0f);
  gl_.UseProgram(depth_program_);
  gl_.UniformMatrix4fv(gl_.GetUniformLocation(depth_program_, "u_light_view_proj"), 1, GL_FALSE,
                       light_view_proj.data());
  for (const auto& [mesh, items] : opaque_) DrawInstances(*mesh, items);
  gl_.Disable(GL_POLYGON_OFFSET_FILL);
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
  if (scene.grid.enabled && scene.grid.extent > 0.0f && scene.grid.spacing > 0.0f) {
    DrawGrid(scene.grid, frame);
  }
  UseLitProgram(frame, false);
  for (const auto& [mesh, items] : opaque_) DrawInstances(*mesh, items);
  if (!translucent_.empty()) DrawTranslucent(camera);
  if (!scene.lines.empty()) DrawLines(scene.lines, frame.view_proj);
  gl_.UseProgram(0);
}

GLuint Renderer::Impl::UseLitProgram(const LitFrame& frame, bool grid) {
  const GLuint p = mesh_programs_[frame.shadows ? 1 : 0][grid ? 1 : 0];
  gl_.UseProgram(p);
  gl_.UniformMatrix4fv(Uniform(p, "u_view_proj"), 1, GL_FALSE, frame.view_proj.data());
  gl_.UniformMatrix4fv(Uniform(p, "u_light_view_proj"), 1, GL_FALSE, frame.light_view_proj.data());
  gl_.Uniform3f(Uniform(p, "u_eye"), frame.eye.x(), frame.eye.y(), frame.eye.z());
  gl_.Uniform3f(Uniform(p, "u_up"), frame.up.x(), frame.up.y(), frame.up.z());
  gl_.Uniform1i(Uniform(p, "u_num_lights"), static_cast<GLint>(frame.num_lights));
  gl_.Uniform3fv(Uniform(p, "u_light_dir"), 4, frame.light_dir.data());
  gl_.Uniform3fv(Uniform(p, "u_light_rgb"), 4, frame.light_rgb.data());
  gl_.Uniform3f(Uniform(p, "u_ambient"), frame.ambient[0], frame.ambient[1], frame.ambient[2]);
  gl_.Uniform1i(Uniform(p, "u_shadow_map"), 0);
  gl_.Uniform1f(Uniform(p, "u_shadow_texel"), 1.0f / internal::kShadowMapSize);
  return p;
}

void Renderer::Impl::DrawGrid(const Grid& g, const LitFrame& frame) {
  const GLuint p = UseLitProgram(frame, true);
  gl_.Uniform2f(Uniform(p, "u_grid_center"), g.center.x(), g.center.y());
  gl_.Uniform1f(Uniform(p, "u_grid_spacing"), g.spacing);
  gl_.Uniform4f(Uniform(p, "u_grid_line"), g.line_rgba[0], g.line_rgba[1], g.line_rgba[2],
                g.line_rgba[3]);
  Material flat;
  flat.specular = 0.0f;
  const Eigen::Matrix4f model =
      internal::Translate(Eigen::Vector3f(g.center.x(), g.center.y(), g.height)) *
      internal::Scale(Eigen::Vector3f(g.extent, g.extent, 1.0f));
  scratch_.assign(1, internal::MakeInstance(model, g.plane_rgba, flat));
  // Pushed back in depth so that shapes resting on the ground do not z-fight with it.
  gl_.Enable(GL_POLYGON_OFFSET_FILL);
  gl_.PolygonOffset(1.0f, 2.0f);
  DrawInstances(quad_, scratch_);
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
